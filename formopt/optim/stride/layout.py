"""The stride NLP's bookkeeping, apart from its transcription: named blocks of the decision
vector (`Blocks`), constraint rows with their bounds (`Rows`), which contact rows are held
kinematically (`held_rows`), and the raw solution (`Solved`)."""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np


class Blocks:
    """Named blocks of one decision vector: shapes, bounds and (once `finish`ed) their
    expressions, slices of one MX symbol `x`, in the order declared."""

    def __init__(self):
        self.names, self.lower, self.upper = [], [], []
        self.shapes, self.offsets, self.size = {}, {}, 0
        self.x: ca.MX | None = None
        self.symbols: list = []

    def add(self, name, shape, lower=-np.inf, upper=np.inf):
        """Declare a block (before `finish`)."""
        self.names.append(name)
        self.lower.append(np.broadcast_to(np.asarray(lower, float), shape).ravel(order="F"))
        self.upper.append(np.broadcast_to(np.asarray(upper, float), shape).ravel(order="F"))
        self.shapes[name], self.offsets[name] = shape, self.size
        self.size += shape[0] * shape[1]

    def finish(self) -> dict:
        """The decision vector x (MX) and each block as a slice of it, by name."""
        self.x = ca.MX.sym("x", self.size)
        self.symbols = [ca.reshape(self.x[self.offsets[k]:self.offsets[k] + self.shapes[k][0] * self.shapes[k][1]],
                                   *self.shapes[k]) for k in self.names]
        return dict(zip(self.names, self.symbols))

    def vector(self):
        return self.x

    def split(self, x) -> dict[str, np.ndarray]:
        """Numeric blocks of a decision vector (each in its shape)."""
        x = np.asarray(x, float).ravel()
        return {k: x[self.offsets[k]:self.offsets[k] + self.shapes[k][0] * self.shapes[k][1]]
                .reshape(self.shapes[k], order="F") for k in self.names}

    def join(self, values: dict) -> np.ndarray:
        return np.concatenate([_shaped(values[k], self.shapes[k]).ravel(order="F")
                               for k in self.names])


def held_rows(rows, sliding: str = "") -> list[int]:
    """Indices of the contact rows held kinematically: all but the sliding point's "t" row."""
    return [k for k, (p, a) in enumerate(rows) if not (p == sliding and a == "t")]


def _shaped(value, shape) -> np.ndarray:
    """value broadcast to shape (a column given as a flat vector is taken as one)."""
    value = np.asarray(value, float)
    if value.ndim == 1 and shape[1] == 1:
        value = value[:, None]
    return np.broadcast_to(value, shape)


class Rows:
    """Constraint rows (SX or MX) with their bounds (scalars or one per row), in order."""

    def __init__(self):
        self.expr, self.lower, self.upper = [], [], []

    def add(self, expr, lower=0.0, upper=0.0):
        expr = ca.vec(expr)
        self.expr.append(expr)
        self.lower.append(np.broadcast_to(np.asarray(lower, float), expr.shape[0]).copy())
        self.upper.append(np.broadcast_to(np.asarray(upper, float), expr.shape[0]).copy())
        return len(self.expr) - 1


@dataclass
class Solved:
    """The raw solution: blocks, IPOPT's statistics, seconds, the parameters; the primal and
    dual values (x, lam_x, lam_g) and the layout of the NLP that produced them (block names,
    number of rows), for a warm start of the same NLP (StrideNLP.resolve)."""

    blocks: dict
    success: bool
    status: str
    iterations: int
    solve_s: float
    objective: float
    x: np.ndarray
    lam_g: np.ndarray
    parameters: dict
    lam_x: np.ndarray | None = None
    layout: tuple = ()
