"""The impact map by conservation of angular momentum (seed eq. 3): an independent method for
mechanics.impact's projection, built from the segments' mass, centre of mass and inertia, not
the mass matrix (tests/mechanics/test_angular_momentum.py compares the two).
"""

from __future__ import annotations

import numpy as np

from .errors import InputError
from .model import Model


def angular_momentum_impact(model: Model, q, qd, point: str) -> np.ndarray:
    """Post-impact velocities by conservation of angular momentum (seed eq. 3), numeric.

    For a single contact point C held at the impact: C's velocity becomes zero, the whole
    system's angular momentum about C is conserved, and so is, about each hinge J between C
    and the free end, that of the bodies beyond J (free hinges transmit no impulsive moment).
    Uses the segments' mass, centre of mass and inertia directly, not the mass matrix.
    """
    q, qd = np.asarray(q, float), np.asarray(qd, float)
    Phi_b = np.asarray(model.constraint_jacobian(q), float)
    groups = _point_groups(model)
    contact_body = next(b for b in model.bodies if point in b.base + b.fixed)
    rows = [Phi_b, model.scatter(np.eye(2), [point])]
    rows.append(_momentum_row(model, q, q[model.cols(point)], model.segments))
    for joint, far in _hinges(model, groups, contact_body.segment):
        rows.append(_momentum_row(model, q, q[model.cols(joint)], far))
    A = np.vstack(rows)
    rhs = np.concatenate([np.zeros(Phi_b.shape[0] + 2), A[Phi_b.shape[0] + 2:] @ qd])
    if np.linalg.matrix_rank(A) < model.n:
        raise InputError("angular-momentum map: the hinges do not determine the motion "
                         "(this method covers open chains with one contact point)")
    return np.linalg.solve(A, rhs)


def _cross_row(arm) -> np.ndarray:
    """Row r such that r @ v = arm x v (planar cross product)."""
    return np.array([[-arm[1], arm[0]]])


def _momentum_row(model: Model, q, origin, segments) -> np.ndarray:
    """(1 x n) map from q' to the angular momentum of `segments` about `origin` (kg m^2/s)."""
    row = np.zeros((1, model.n))
    for seg in segments:
        s = model.body[seg]
        C = model.com_matrix(seg)
        row += s.mass * _cross_row(C @ q - origin) @ C
        body = next((b for b in model.bodies if b.segment == seg), None)
        if body is not None and s.inertia_com > 0:
            ri, rj = (q[model.cols(p)] for p in body.base)
            d = rj - ri
            P = model.scatter(np.hstack([-np.eye(2), np.eye(2)]), body.base)  # q' -> r_j' - r_i'
            row += s.inertia_com / (d @ d) * _cross_row(d) @ P
    return row


def _point_groups(model: Model) -> dict[str, str]:
    """Representative point of each point, merging coincident points (union-find)."""
    parent = {p.name: p.name for p in model.points}

    def find(p):
        while parent[p] != p:
            p = parent[p]
        return p

    for a, c in model.coincident:
        parent[find(a)] = find(c)
    return {p: find(p) for p in parent}


def _hinges(model: Model, groups, contact_segment):
    """(hinge point, segments of one branch beyond it seen from the contact), for every
    branch of every hinge: a chain has one branch beyond each hinge, a tree may have more
    (trunk and swing leg beyond the stance hip)."""
    touches = {b.segment: {groups[p] for p in b.base + b.fixed} for b in model.bodies}
    touches.update({pm.segment: {groups[pm.point]} for pm in model.point_masses})
    rigid = {b.segment for b in model.bodies}
    hinges = [g for g in set(groups.values())
              if sum(g in touches[s] for s in rigid) >= 2]

    def component(start, g, allowed):
        reached, frontier = {start}, [start]
        while frontier:
            seg = frontier.pop()
            for other in allowed:
                if other not in reached and (touches[seg] & touches[other]) - {g}:
                    reached.add(other)
                    frontier.append(other)
        return reached

    for g in sorted(hinges):
        near = component(contact_segment, g, touches)
        rest = [s for s in touches if s not in near]
        while rest:
            branch = component(rest[0], g, rest)
            if branch & rigid:  # a lone point mass at the hinge has no moment about it
                yield g, sorted(branch)
            rest = [s for s in rest if s not in branch]
