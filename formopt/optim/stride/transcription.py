"""The transcriptions of the stride's collocation (collocation.StrideNLP, `settings.transcription`):
how many columns a phase of n intervals has, the defects that tie the states X to their rates
x', the quadrature of the node integrands, and the smoothing that closes the scheme's own null
mode (problem.SMOOTHING). Each scheme is a class of static methods, picked by name
(`TRANSCRIPTIONS`: problem.TRANSCRIPTIONS' names).

The mesh: a phase of duration T and n intervals has its mesh points at fractions tau_k of T
(`fractions`, graded toward both of the phase's ends by StrideSettings.grading), interval k of
length h s_k with h = T / n the uniform one and s_k = n (tau_k+1 - tau_k) (`steps`); each scheme
takes h and s. Every place that needs a column's time reads `times`."""

from __future__ import annotations

import casadi as ca
import numpy as np

from . import problem


def fractions(n: int, grading: float) -> np.ndarray:
    """The mesh points' fractions 0 = tau_0 < ... < tau_n = 1 of a phase's duration, graded
    toward both ends by g = `grading` (0 to 1): tau = (1 - g) s + g (1 - cos(pi s)) / 2 at the
    uniform s = k / n, a blend of the uniform mesh and the cosine (Chebyshev-Lobatto) one. The
    first and last intervals are (1 - g) + g n (1 - cos(pi / n)) / 2, about (1 - g) + g pi^2 / (4 n),
    times a uniform one (0.62 at g = 0.5 and 0.32 at g = 0.9 for n = 10; pi^2 / (4 n), O(1/n^2) in
    all, at g = 1), the middle ones about (1 - g) + g pi / 2 times. The map is smooth (a uniform
    mesh in s of a smooth change of variable t = T tau(s)), so the schemes keep their order inside
    the phase, while a layer a phase's end column carries (an impact's transient) costs in
    proportion to that end interval's length."""
    s = np.linspace(0.0, 1.0, n + 1)
    return (1 - grading) * s + grading * (1 - np.cos(np.pi * s)) / 2


def steps(n: int, grading: float) -> np.ndarray:
    """Each interval's length over a uniform one's, s_k = n (tau_k+1 - tau_k) (`fractions`): n
    values summing to n, exactly ones at grading 0 (the uniform mesh's NLP as before, bit for bit)."""
    return n * np.diff(fractions(n, grading)) if grading else np.ones(n)


def times(scheme, T, n: int, grading: float) -> np.ndarray:
    """The columns' times (s, from the phase's start) of a phase of n intervals over T (s) in a
    scheme of TRANSCRIPTIONS: T times its `column_fractions` (np.linspace(0, T, columns) at grading
    0, as before, bit for bit)."""
    return T * scheme.column_fractions(n, grading) if grading else np.linspace(0.0, T, scheme.columns(n))


def _per_interval(M, s: np.ndarray):
    """M (a column per interval) with column k times s_k (M itself on a uniform mesh)."""
    if (s == 1).all():
        return M
    return M * ca.repmat(ca.DM(s).T, M.shape[0], 1)


class Trapezoid:
    """The trapezoidal rule: n + 1 columns (the mesh points), on interval k of length h_k = h s_k
    (`steps`)

        x_k+1 - x_k = h_k/2 (x'_k + x'_k+1),   quadrature weights (h_k-1 + h_k) / 2 (h_-1 = h_n = 0)

    (second order: the energy balance closes to O(h^2)). Its smoothing: sum h_k |A_k+1 - A_k|^2
    (accelerations that alternate node to node leave the defects unchanged)."""

    @staticmethod
    def columns(n: int) -> int:
        return n + 1

    @staticmethod
    def intervals(columns: int) -> int:
        return columns - 1

    @staticmethod
    def column_fractions(n: int, grading: float) -> np.ndarray:
        """The columns' fractions of the phase's duration: the mesh points'."""
        return fractions(n, grading)

    @staticmethod
    def weights(h, s: np.ndarray):
        """The quadrature's weights (a row of `columns(n)`), h = T / n, s the relative steps."""
        return h * ca.DM((np.r_[s, 0.0] + np.r_[0.0, s]) / 2).T

    @staticmethod
    def defects(X, D, h, s: np.ndarray):
        """The rows that tie states X to their rates D = x' (one column per column)."""
        return X[:, 1:] - X[:, :-1] - 0.5 * h * _per_interval(D[:, :-1] + D[:, 1:], s)

    @staticmethod
    def smoothing(A, h, s: np.ndarray):
        """The smoothing's sum (problem.SMOOTHING) of the accelerations A (a column per column; with
        muscles their activations' rates below them: actuation.MuscleDriven.smoothed)."""
        return h * ca.sumsqr(_per_interval(A[:, 1:] - A[:, :-1], np.sqrt(s)))


class HermiteSimpson:
    """Hermite-Simpson collocation, separated form: 2n + 1 columns (mesh points at even
    columns, interval midpoints at odd ones, each at its interval's middle: the node model holds
    at both), on interval k of length h (h_k = h s_k on a graded mesh, `steps`)

        x_m = (x_k + x_k+1)/2 + h/8 (x'_k - x'_k+1),   x_k+1 - x_k = h/6 (x'_k + 4 x'_m + x'_k+1),

    quadrature weights h/6 (1, 4, 2, 4, ..., 2, 4, 1) (Simpson's rule: fourth order; h_k/6 (1, 4, 1)
    on each interval, summed at the shared points). Its
    smoothing: sum h |A_k - 2 A_m + A_k+1|^2 over the intervals, the accelerations' curvature
    within each: (+c, -c/2, +c) leaves the velocity defects unchanged and costs 9 h c^2 an
    interval, a smooth A h (h/2)^4 |A''|^2 an interval, (h/2)^4 int |A''|^2 dt in all (its share
    falls as h^4, the trapezoid's h^2 int |A'|^2 dt as h^2)."""

    @staticmethod
    def columns(n: int) -> int:
        return 2 * n + 1

    @staticmethod
    def intervals(columns: int) -> int:
        return (columns - 1) // 2

    @staticmethod
    def column_fractions(n: int, grading: float) -> np.ndarray:
        """The columns' fractions of the phase's duration: the mesh points' at even columns, their
        intervals' middles at odd ones."""
        tau = fractions(n, grading)
        return np.insert(tau, np.arange(1, n + 1), (tau[:-1] + tau[1:]) / 2)

    @staticmethod
    def weights(h, s: np.ndarray):
        w = np.zeros(2 * s.size + 1)
        w[1::2] = 4.0 * s
        w[:-1:2] += s
        w[2::2] += s
        return h / 6 * ca.DM(w).T

    @staticmethod
    def defects(X, D, h, s: np.ndarray):
        x0, xm, x1 = X[:, :-2:2], X[:, 1::2], X[:, 2::2]
        d0, dm, d1 = D[:, :-2:2], D[:, 1::2], D[:, 2::2]
        return ca.vertcat(xm - 0.5 * (x0 + x1) - h / 8 * _per_interval(d0 - d1, s),
                          x1 - x0 - h / 6 * _per_interval(d0 + 4 * dm + d1, s))

    @staticmethod
    def smoothing(A, h, s: np.ndarray):
        """The smoothing's sum (problem.SMOOTHING) of the accelerations A (2n + 1 columns, mesh
        points even; with muscles their activations' rates below them): sum over the intervals of
        h_k |A_k - 2 A_m + A_k+1|^2."""
        return h * ca.sumsqr(_per_interval(A[:, :-2:2] - 2 * A[:, 1::2] + A[:, 2::2], np.sqrt(s)))


TRANSCRIPTIONS: dict[str, type[Trapezoid] | type[HermiteSimpson]] = dict(
    zip(problem.TRANSCRIPTIONS, (Trapezoid, HermiteSimpson)))
