"""Rigid fits of a marker cluster to its standing shape: Kabsch's rotation and translation,
the fit's residual, and the cluster's angular speed from its fitted rotations."""

from __future__ import annotations

import numpy as np


def kabsch(reference, current) -> tuple[np.ndarray, np.ndarray]:
    """Rotations R and translations t with current ~ reference @ R.T + t (rows are markers),
    least squares, det R = +1 (Kabsch 1976).

    reference: (k, 3); current: (k, 3) or a stack (..., k, 3), one fit per frame;
    R: (..., 3, 3), t: (..., 3).
    """
    a0, b0 = reference.mean(axis=0), current.mean(axis=-2)
    H = np.swapaxes(current - b0[..., None, :], -1, -2) @ (reference - a0)  # = ((ref)^T cur)^T
    u, _, vt = np.linalg.svd(np.swapaxes(H, -1, -2))
    v, ut = np.swapaxes(vt, -1, -2), np.swapaxes(u, -1, -2)
    d = np.sign(np.linalg.det(v @ ut))
    D = np.zeros(d.shape + (3, 3))
    D[..., 0, 0] = D[..., 1, 1] = 1.0
    D[..., 2, 2] = d
    R = v @ D @ ut
    return R, b0 - a0 @ np.swapaxes(R, -1, -2)


def fit_residual(reference, current, R, t) -> np.ndarray:
    """Rms distance (m) per frame between `current` (frames, k, 3) and the fitted cluster
    `reference @ R.T + t` (reference (k, 3), R (frames, 3, 3), t (frames, 3))."""
    fitted = np.einsum("fij,kj->fki", R, reference) + t[:, None, :]
    return np.sqrt(np.mean(np.sum((fitted - current) ** 2, axis=-1), axis=-1))


def angular_velocity(R, rate: float) -> np.ndarray:
    """omega (frames, 3; rad/s, lab frame) of rotations R (frames, 3, 3) sampled at `rate` Hz,
    by central differences (one-sided at the ends): the axis-angle vector of
    D = R[k+1] R[k-1]^T over 2 / rate, from its skew part, (D - D^T) / 2 = sin(angle) [axis]x."""
    if len(R) < 2:
        return np.zeros((len(R), 3))
    k = np.arange(len(R))
    after, before = np.minimum(k + 1, len(R) - 1), np.maximum(k - 1, 0)
    D = R[after] @ np.swapaxes(R[before], -1, -2)
    axis = 0.5 * np.stack([D[:, 2, 1] - D[:, 1, 2], D[:, 0, 2] - D[:, 2, 0], D[:, 1, 0] - D[:, 0, 1]], axis=1)
    sine = np.linalg.norm(axis, axis=1)
    angle = np.arctan2(sine, (np.einsum("fii->f", D) - 1.0) / 2.0)
    scale = np.divide(angle, sine, out=np.ones_like(angle), where=sine > 1e-12)
    return axis * (scale * rate / (after - before))[:, None]
