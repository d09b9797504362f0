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

**Repeated frequencies.** Identical beams give equal frequencies, and the eigenvectors of a
repeated frequency are any basis of its eigenspace: one speed's solver may return blade 1's mode,
the next a mix of blades 1 and 2, so the MAC of single vectors means nothing there. Frequencies
within :data:`SAME_FREQUENCY` of each other form one eigenspace (:func:`eigenspaces`);
:func:`follow` matches a branch to a *space* by its subspace MAC (the squared cosine of the
angle between the branch's previous shape and the space, ||Q^H a||^2 / ||a||^2 for an
orthonormal basis Q), and then turns the space's basis onto the branches it continues (the
orthogonal Procrustes rotation: the vectors of the space closest to the previous shapes), so a
branch continues as the member of the eigenspace nearest to what it was.
"""

from __future__ import annotations

import numpy as np

from hubbeam.system.parts import BEAM_MOTIONS

#: the parts of a mode's kinetic energy, in the order a label joins them (``base``: a moving
#: base's own body)
MOTIONS = BEAM_MOTIONS + ("hub", "base")
#: a part at least this share of the kinetic energy names the mode alone
DOMINANT = 0.6
#: frequencies closer than this (relative) are one repeated frequency: their modes one eigenspace
#: (identical beams' frequencies agree to about 1e-8 with the rotating-state differences)
SAME_FREQUENCY = 1e-6
#: a match whose (subspace) MAC is below this is reported as uncertain
CONFIDENT_MAC = 0.8
#: a branch's frequency may change by this share between two speeds (or by the speed step's
#: plausible change, whichever is larger) before its match is penalised and called uncertain
PLAUSIBLE_CHANGE = 0.1


def plausible_change(frequency_hz, step_hz: float):
    """The largest change (Hz) of a branch at ``frequency_hz`` between two speeds that is not
    suspect: the speed step's plausible change ``step_hz`` or :data:`PLAUSIBLE_CHANGE` of the
    frequency, whichever is larger."""
    return np.maximum(step_hz, PLAUSIBLE_CHANGE * np.abs(np.asarray(frequency_hz, dtype=float)))


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


def eigenspaces(frequencies, same: float = SAME_FREQUENCY) -> list[np.ndarray]:
    """The indices of ascending ``frequencies`` grouped into repeated frequencies: a frequency
    within ``same`` (relative) of the previous one joins its group."""
    f = np.asarray(frequencies, dtype=float)
    groups: list[list[int]] = []
    for i, value in enumerate(f):
        if groups and value - f[groups[-1][-1]] <= same * max(abs(value), 1e-300):
            groups[-1].append(i)
        else:
            groups.append([i])
    return [np.array(g, dtype=int) for g in groups]


def orthonormal(basis: np.ndarray) -> np.ndarray:
    """An orthonormal basis (columns) of the span of ``basis``'s columns."""
    q, r = np.linalg.qr(np.asarray(basis))
    return q[:, np.abs(np.diagonal(r)) > 1e-12 * max(np.max(np.abs(np.diagonal(r)), initial=0.0), 1e-300)]


def subspace_mac(shapes: np.ndarray, space: np.ndarray) -> np.ndarray:
    """For each column a of ``shapes`` the share of it in the span of ``space``'s columns,
    ||Q^H a||^2 / ||a||^2 (Q orthonormal): the squared cosine of the angle between a and the
    space; for a one-column space the MAC."""
    q = orthonormal(space)
    a = np.asarray(shapes)
    return np.sum(np.abs(np.conj(q).T @ a) ** 2, axis=0) / np.maximum(np.real(np.sum(np.conj(a) * a, axis=0)), 1e-300)


def follow(previous: np.ndarray, previous_hz: np.ndarray, spaces, step_hz: float):
    """Continue the branches ``previous`` (n x m shapes at frequencies ``previous_hz``) into
    ``spaces``, a list of (basis (n x d), frequencies (d,)) of the next speed: each space offers d
    places. The assignment minimises the summed 1 - subspace MAC (:func:`subspace_mac`) plus a
    penalty 0.5 (1 - exp(-(change / allowed)^2 / 4)), up to 0.5, for a frequency change beyond
    the plausible one (:func:`plausible_change` of ``step_hz``, Hz), so that a branch never jumps
    to a far frequency for a slightly better shape. Within a space, its basis is turned onto the branches
    it takes (orthogonal Procrustes), so a branch continues as the member nearest to its previous
    shape. Returns (shapes (n x m), frequencies (m,), MAC of each branch with its previous shape,
    space of each branch (-1: none left)); a branch without a place keeps NaN."""
    from scipy.optimize import linear_sum_assignment  # loaded when first needed: it is slow to import

    previous = np.asarray(previous)
    m = previous.shape[1]
    bases = [orthonormal(b) for b, _ in spaces]
    centre = np.array([float(np.mean(f)) for _, f in spaces])
    owner = np.concatenate([np.full(q.shape[1], i) for i, q in enumerate(bases)]).astype(int) if bases else np.zeros(0, int)
    share = np.array([subspace_mac(previous, q) for q in bases]).reshape(len(bases), m).T  # m x spaces
    change = np.abs(centre[None, :] - np.asarray(previous_hz, dtype=float)[:, None])
    allowed = plausible_change(previous_hz, step_hz)[:, None]
    cost = 1.0 - share + 0.5 * (1.0 - np.exp(-np.nan_to_num(change / allowed, nan=0.0) ** 2 / 4.0))
    cost = np.nan_to_num(cost, nan=2.0)  # a branch that ended (no shape) takes what is left
    rows, cols = linear_sum_assignment(cost[:, owner]) if owner.size else (np.zeros(0, int), np.zeros(0, int))
    shapes = np.full(previous.shape, np.nan, dtype=complex)
    freqs, macs, where = np.full(m, np.nan), np.full(m, np.nan), np.full(m, -1)
    for s, (basis, f) in enumerate(spaces):
        branches = rows[owner[cols] == s]
        if not branches.size:
            continue
        q = bases[s]
        u, _, vh = np.linalg.svd(np.conj(q).T @ previous[:, branches], full_matrices=False)
        turned = q @ (u @ vh)
        coef = np.linalg.lstsq(np.asarray(basis), turned, rcond=None)[0]
        weight = np.abs(coef) ** 2
        shapes[:, branches] = turned
        freqs[branches] = (np.asarray(f, dtype=float) @ weight) / np.maximum(weight.sum(axis=0), 1e-300)
        macs[branches] = np.diagonal(mac_matrix(previous[:, branches], turned))
        where[branches] = s
    return shapes, freqs, macs, where


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


def blade_vectors(system, x, F, shapes, points_per_element: int = 2) -> np.ndarray:
    """Every beam's motion in a mode, measured alike on each beam in its own axis frame, for
    the multi-blade coordinates (:mod:`hubbeam.solvers.multiblade`): (modes, beams, m), m = the
    centre line's (axial, flap, lag) displacement at ``points_per_element`` stations per element
    and the twist times half the root section's larger side (so it compares with the
    displacements), per unit of the modal coordinate. A beam a mode does not move is zero
    without evaluating it. The beams must have one mesh (identical beams)."""
    shapes = np.asarray(shapes)
    frames = np.ones(shapes.shape[0], dtype=bool)  # the coordinates of no beam: base, hub, joints
    for k in range(len(system.beams)):
        frames[system.layout.beam_x(k)] = False
    frames_move = np.any(shapes[frames] != 0.0, axis=0)
    out = None
    for k, part, q, chart in system.parts(x, F):
        xs = part.stations(points_per_element)
        half = 0.5 * max(part.section_size(0.0))
        if out is None:
            out = np.zeros((shapes.shape[1], len(system.beams), 4 * xs.size), dtype=complex)
        for i in np.flatnonzero(frames_move | np.any(shapes[system.layout.beam_x(k)] != 0.0, axis=0)):
            d, t = system.span_shape(k, x, F, shapes[:, i], xs)
            out[i, k] = np.concatenate([np.ravel(d), half * np.ravel(t)])
    return out
