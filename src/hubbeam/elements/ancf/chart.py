"""Choice and replacement of the reference-director chart of the ANCF beam.

The chart F = [d f2 f3] (see :mod:`.frame`) is singular only where a tangent points
along -d. :func:`choose_director` picks the d that keeps every tangent as far from
-d as the candidates allow; :func:`remap_chart` re-expresses the twist coordinates in a
new chart. The remapping is exact at the nodes for theta_1 (the frame at every node is
unchanged) and for theta_1' it uses the invariance of the torsion kappa1 = theta_1' +
tau0, where tau0 = -d.(tau x tau') / (1 + d.tau) is the chart's own twist rate, with
tau' averaged over the two elements that meet at the node (tau' jumps there).
Inside an element the Hermite-interpolated twist then differs from the old one by the
cubic interpolation error of the chart change along the element, which vanishes for a
straight element; :func:`remap_chart` reports the largest change of the twist field.
"""

from __future__ import annotations

import numpy as np

from hubbeam.elements.ancf.frame import section_frame
from hubbeam.errors import ConvergenceError

#: a nodal slope |r'| = 1 + axial strain below this is a crushed, unphysical state (no frame)
SLOPE_FLOOR = 1.0e-3


def frame_from_director(d: np.ndarray, hint: np.ndarray | None = None) -> np.ndarray:
    """A right-handed orthonormal frame [d f2 f3] with first column ``d``."""
    d = np.asarray(d, dtype=float)
    d = d / np.linalg.norm(d)
    if hint is None or abs(np.dot(hint, d)) > 0.9:
        axes = np.eye(3)
        hint = axes[np.argmin(np.abs(axes @ d))]
    f2 = hint - np.dot(hint, d) * d
    f2 /= np.linalg.norm(f2)
    return np.column_stack([d, f2, np.cross(d, f2)])


def choose_director(tangents: np.ndarray) -> np.ndarray:
    """Director d maximising min(d . tau) over the unit tangents (rows of ``tangents``)."""
    t = np.asarray(tangents, dtype=float)
    t = t / np.linalg.norm(t, axis=1, keepdims=True)
    candidates = [*np.eye(3), *(-np.eye(3))]
    mean = t.mean(axis=0)
    if np.linalg.norm(mean) > 1e-8:
        candidates.append(mean / np.linalg.norm(mean))
    # normal of the best-fit plane through the tangents (a planar curve: d along it is optimal)
    _, _, vt = np.linalg.svd(t, full_matrices=True)
    candidates += [vt[-1], -vt[-1]]
    # a few refinement steps of the minimax problem: move d towards the worst tangent
    best = max(candidates, key=lambda c: np.min(t @ c))
    for _ in range(50):
        worst = t[np.argmin(t @ best)]
        trial = best + 0.2 * (worst - np.dot(worst, best) * best)
        trial /= np.linalg.norm(trial)
        if np.min(t @ trial) > np.min(t @ best) + 1e-12:
            best = trial
        else:
            break
    return best / np.linalg.norm(best)


def chart_twist_rate(d: np.ndarray, tau: np.ndarray, dtau: np.ndarray) -> float:
    """tau0 = -d.(tau x tau') / (1 + d.tau): twist rate of the chart frame along the beam."""
    return float(-np.dot(d, np.cross(tau, dtau)) / (1.0 + np.dot(d, tau)))


def twist_offset(F_old: np.ndarray, F_new: np.ndarray, r_prime: np.ndarray) -> float:
    """delta with R0_old(tau) = R0_new(tau) Rx(delta): theta_new = theta_old + delta."""
    _, m_old, _ = section_frame(F_old.T @ r_prime, 0.0)
    _, m_new, n_new = section_frame(F_new.T @ r_prime, 0.0)
    m_old_g = F_old @ m_old
    return float(np.arctan2(np.dot(m_old_g, F_new @ n_new), np.dot(m_old_g, F_new @ m_new)))


def remap_chart(nodes: np.ndarray, node_dtau: np.ndarray, F_old: np.ndarray, F_new: np.ndarray) -> np.ndarray:
    """Nodal coordinates (n_nodes, 8) re-expressed in chart ``F_new``.

    ``node_dtau`` (n_nodes, 3) is d(tau)/dx at each node (element average). Positions
    and slopes are unchanged; theta_1 and theta_1' change so that the frame and the
    torsion at every node are unchanged.
    """
    out = np.array(nodes, dtype=float, copy=True)
    lengths = np.linalg.norm(out[:, 3:6], axis=1)
    bad = np.flatnonzero(~(lengths > SLOPE_FLOOR))  # also NaN
    if bad.size:
        raise ConvergenceError(
            f"the slope r' at node {int(bad[0])} of the beam has collapsed to length {lengths[bad[0]]:.2g} "
            "(Newton converged to a crushed, unphysical state, which has no section frame): the load is too large "
            "for the mesh or the steps; try more beam.elements, and more analysis.load_steps (statics) or a smaller "
            "analysis.dt (time integration)")
    deltas = np.array([twist_offset(F_old, F_new, nd[3:6]) for nd in nodes])
    # keep the offset continuous along the beam (it is defined modulo 2 pi)
    deltas = np.unwrap(deltas)
    for i, nd in enumerate(nodes):
        tau = nd[3:6] / np.linalg.norm(nd[3:6])
        out[i, 6] = nd[6] + deltas[i]
        out[i, 7] = nd[7] + chart_twist_rate(F_old[:, 0], tau, node_dtau[i]) - chart_twist_rate(F_new[:, 0], tau, node_dtau[i])
    return out
