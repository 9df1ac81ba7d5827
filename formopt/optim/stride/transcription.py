"""The transcriptions of the stride's collocation (collocation.StrideNLP, `settings.transcription`):
how many columns a phase of n intervals has, the defects that tie the states X to their rates
x', the quadrature of the node integrands, and the smoothing that closes the scheme's own null
mode (problem.SMOOTHING). Each scheme is a class of static methods, picked by name
(`TRANSCRIPTIONS`: problem.TRANSCRIPTIONS' names)."""

from __future__ import annotations

import casadi as ca
import numpy as np

from . import problem


class Trapezoid:
    """The trapezoidal rule: n + 1 columns (the mesh points), on each interval of length h

        x_k+1 - x_k = h/2 (x'_k + x'_k+1),   quadrature weights h (1/2, 1, ..., 1, 1/2)

    (second order: the energy balance closes to O(h^2)). Its smoothing: sum h |A_k+1 - A_k|^2
    (accelerations that alternate node to node leave the defects unchanged)."""

    @staticmethod
    def columns(n: int) -> int:
        return n + 1

    @staticmethod
    def weights(n: int, h):
        """The quadrature's weights (a row of `columns(n)`)."""
        w = np.ones((1, n + 1))
        w[0, [0, -1]] = 0.5
        return h * ca.DM(w)

    @staticmethod
    def defects(X, D, h):
        """The rows that tie states X to their rates D = x' (one column per column)."""
        return X[:, 1:] - X[:, :-1] - 0.5 * h * (D[:, :-1] + D[:, 1:])

    @staticmethod
    def smoothing(A, h):
        """The smoothing's sum (problem.SMOOTHING) of the accelerations A (a column per column)."""
        return h * ca.sumsqr(A[:, 1:] - A[:, :-1])


class HermiteSimpson:
    """Hermite-Simpson collocation, separated form: 2n + 1 columns (mesh points at even
    columns, interval midpoints at odd ones: the node model holds at both), on each interval

        x_m = (x_k + x_k+1)/2 + h/8 (x'_k - x'_k+1),   x_k+1 - x_k = h/6 (x'_k + 4 x'_m + x'_k+1),

    quadrature weights h/6 (1, 4, 2, 4, ..., 2, 4, 1) (Simpson's rule: fourth order). Its
    smoothing: sum h |A_k - 2 A_m + A_k+1|^2 over the intervals, the accelerations' curvature
    within each: (+c, -c/2, +c) leaves the velocity defects unchanged and costs 9 h c^2 an
    interval, a smooth A h (h/2)^4 |A''|^2 an interval, (h/2)^4 int |A''|^2 dt in all (its share
    falls as h^4, the trapezoid's h^2 int |A'|^2 dt as h^2)."""

    @staticmethod
    def columns(n: int) -> int:
        return 2 * n + 1

    @staticmethod
    def weights(n: int, h):
        w = np.full((1, 2 * n + 1), 2.0)
        w[0, 1::2] = 4.0
        w[0, [0, -1]] = 1.0
        return h / 6 * ca.DM(w)

    @staticmethod
    def defects(X, D, h):
        x0, xm, x1 = X[:, :-2:2], X[:, 1::2], X[:, 2::2]
        d0, dm, d1 = D[:, :-2:2], D[:, 1::2], D[:, 2::2]
        return ca.vertcat(xm - 0.5 * (x0 + x1) - h / 8 * (d0 - d1), x1 - x0 - h / 6 * (d0 + 4 * dm + d1))

    @staticmethod
    def smoothing(A, h):
        """The smoothing's sum (problem.SMOOTHING) of the accelerations A (2n + 1 columns, mesh
        points even): sum over the intervals of h |A_k - 2 A_m + A_k+1|^2."""
        return h * ca.sumsqr(A[:, :-2:2] - 2 * A[:, 1::2] + A[:, 2::2])


TRANSCRIPTIONS: dict[str, type[Trapezoid] | type[HermiteSimpson]] = dict(
    zip(problem.TRANSCRIPTIONS, (Trapezoid, HermiteSimpson)))
