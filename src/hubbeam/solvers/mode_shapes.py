"""What a mode is: its kinetic-energy split and label, its shape along the span, and the
modal assurance criterion that follows a mode from one hub speed to the next.

**Split and label.** A mode shape u about the configuration x is a rate of the coordinates;
the kinetic energy of the system moving at u is split into the hub's and, for every beam in
its own directions, the ``flap`` (centre line along j_h, out of the hub plane), ``lag`` (along
the beam's k_k, in the hub plane across the beam), ``axial`` (along the beam axis) and
``torsion`` (section rotation about the beam axis) parts
(:meth:`hubbeam.system.multibody.MultibodySystem.kinetic_energy_split`). The fractions add up to
1. The label is the largest part's name; when that part is below :data:`DOMINANT` of the
total, the two largest joined by "+" in the order of :data:`MOTIONS` (``"flap+lag"``).

**MAC.** MAC(a, b) = |a^H b|^2 / ((a^H a)(b^H b)) of two shapes over the same coordinates
(1: the same shape, 0: orthogonal); :func:`match_modes` pairs the modes of consecutive
speeds by the assignment that maximises the summed MAC (scipy's linear_sum_assignment on
1 - MAC), so a branch keeps its shape where frequencies cross.
"""

from __future__ import annotations

import numpy as np

from hubbeam.system.parts import BEAM_MOTIONS

#: the parts of a mode's kinetic energy, in the order a label joins them (``base``: a moving
#: base's own body)
MOTIONS = BEAM_MOTIONS + ("hub", "base")
#: a part at least this share of the kinetic energy names the mode alone
DOMINANT = 0.6


def motions_of(system) -> tuple[str, ...]:
    """The parts a mode's kinetic energy can have in ``system``: :data:`MOTIONS` and, on joints,
    the hinges' rigid rotations ("flap hinge", "lag hinge", ...:
    :meth:`~hubbeam.system.multibody.MultibodySystem.hinge_labels`)."""
    return MOTIONS + system.hinge_labels()


def energy_fractions(system, x, F, shape) -> dict[str, float]:
    """The shares (summing to 1) of a mode's kinetic energy in each part of :func:`motions_of`
    the system has (``base`` only with a moving base, the hinges only on joints): a joint's
    rigid rotation psi' e x (r - r_J) is its hinge's share, the rest split as :data:`MOTIONS`
    (:meth:`~hubbeam.system.multibody.MultibodySystem.mode_energy_split`)."""
    split = system.mode_energy_split(x, F, shape)
    total = sum(split.values())
    if not total > 0.0:
        raise ValueError("a mode shape without kinetic energy has no energy split")
    return {k: split[k] / total for k in motions_of(system) if k in split}


def mode_label(fractions: dict[str, float], dominant: float = DOMINANT) -> str:
    """The largest part's name, or the two largest joined by "+" (in the order of
    :data:`MOTIONS`, then the hinges) when the largest is below ``dominant``."""
    present = [k for k in MOTIONS if k in fractions] + [k for k in fractions if k not in MOTIONS]
    ranked = sorted(present, key=lambda k: -fractions[k])
    if fractions[ranked[0]] >= dominant:
        return ranked[0]
    return "+".join(k for k in present if k in ranked[:2])


def mac_matrix(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """MAC between the columns of a (n x p) and b (n x r): a p x r array in [0, 1]."""
    a, b = np.asarray(a), np.asarray(b)
    cross = np.abs(np.conj(a).T @ b) ** 2
    na = np.real(np.sum(np.conj(a) * a, axis=0))
    nb = np.real(np.sum(np.conj(b) * b, axis=0))
    return cross / np.maximum(np.outer(na, nb), 1e-300)


def match_modes(previous: np.ndarray, current: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For every column of ``previous`` the column of ``current`` (at least as many) that
    continues it, by the assignment that maximises the summed MAC: (indices, their MAC)."""
    from scipy.optimize import linear_sum_assignment  # loaded when first needed: it is slow to import

    if np.shape(current)[1] < np.shape(previous)[1]:
        raise ValueError(f"{np.shape(current)[1]} modes cannot continue {np.shape(previous)[1]}")
    mac = mac_matrix(previous, current)
    rows, cols = linear_sum_assignment(1.0 - mac)
    index = np.empty(mac.shape[0], dtype=int)
    index[rows] = cols
    return index, mac[np.arange(mac.shape[0]), index]


def span_shapes(system, x, F, shapes, points_per_element: int = 8):
    """Each beam's centre-line displacement (axial, flap, lag) and section twist along its span
    for every mode (columns of ``shapes``): a list over beams of (stations (n,) m,
    displacement (modes, n, 3), twist (modes, n)), in the units of the shapes (per unit of the
    modal coordinate), complex for complex shapes."""
    out = []
    for k, part, q, chart in system.parts(x, F):
        xs = part.stations(points_per_element)
        disp, twist = [], []
        for u in np.asarray(shapes).T:
            d, t = system.span_shape(k, x, F, u, xs)
            disp.append(d)
            twist.append(t)
        out.append((xs, np.array(disp), np.array(twist)))
    return out
