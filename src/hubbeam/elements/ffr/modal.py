"""Modal reduction of the FFR beam: ``FfrBeam(..., modes=N)``, scenario key ``beam.modes``.

**What is reduced.** Every FFR term is a contraction of the nodal deformation coordinates p
(or p') with the body's invariants or with rows over p (:mod:`hubbeam.elements.ffr.body`).
A reduced beam is the nodal beam with p = B eta, B a fixed basis, so every invariant and row
maps exactly, once, when the beam is built:

    Sbar B,  J[..., B],  B^T II B (last two axes),  B^T Mff B,  B^T K B (and so the structural
    damping c B^T K B),
    centre-line rows N B,  element-mean strain rows a_e B and B^T G_e B,
    displacement, rotation and strain rows (through ``FfrBeam._scatter``) times B.

Everything else (M_v, Q_v, Q_g, the elastic force and tangent, sensors, drag) is the nodal
code, unchanged; the system layer sees an FfrBeam with ``ndof`` = the number of columns of B.
``elements`` and ``element_length`` still describe the underlying mesh.

**The basis.** Without geometric stiffening, B = Phi: the N lowest clamped-free modes of
K p = w^2 Mff p (body frame held; the tip body is in Mff), Mff-normalised, so
B^T Mff B = I and B^T K B = diag(w^2) (``frequencies_hz``; ``max_frequency_hz`` the highest
kept one).

With ``geometric_stiffening`` the basis is [Phi_b, E_u]: the N lowest modes of the beam with
its axial coordinates u0 held (bending and torsion), plus the nodal u0 coordinates themselves
(one per element), so ndof = N + elements. The reason, measured: the stiffening lives in the
element-mean strain eps_e = a_e p + p^T G_e p / 2; the centrifugal tension needs the axial
stretch, and an inextensible bending deflection needs u0' to cancel the foreshortening element
by element. The plate's axial modes are far up the spectrum (879 Hz, the ~30th mode with 8
elements), so projecting on the N lowest modes alone (``reduce(..., axial="modal")``) keeps no
axial freedom:

* at steady spin eta carries no tension and the stiffening vanishes: first flap frequency of
  the rotating plate below 0.978 Hz (its value at rest) for every N up to 16 against 1.335 Hz
  nodal (-26.8 %), right only from N = 30;
* a finite deflection locks (eps_e = p^T G_e p / 2 with nothing to relax it): exp1-like run
  below, N = 8: largest tip sag over 1 s 0.011 m against 0.408 m nodal.

With the nodal u0 kept the stiffened model converges as fast as the plain one (tables); its
tip sag history is the nodal one to 4e-5 of its range.

**How many modes.** Measured on the reference plate (L = 1.45 m, 50 x 2.5 mm aluminium),
6 elements (36 nodal coordinates), against the nodal FFR of the same mesh (fresh Newton
matrix each step; the default adaptive iteration's own error, ~6e-4 of the spin-up lag,
would hide the small ones):

exp1-like (free hub 9.557 kg m^2, R = 0.35 m, beta = 45 deg, released from rest under
gravity, no drag): max |error| of the P1 strain (x = 0.3 m, upper surface) over 1 s / its
range (8.6e-4).
exp2-like (prescribed Kane spin-up to 3 rad/s in T = 2 s, R = 0.55 m, beta = 0 so the lag
is along the weak axis, gravity): max |error| of the tangential tip deflection over 2.5 s /
its largest value (0.278 m plain, 0.264 m stiffened).
Static residual: the share of the static tip deflection under exp1's gravity the kept modes
miss (:func:`static_residual`, ``tip``).

    N   | exp1 P1 plain | exp1 P1 stiffened | exp2 lag plain | exp2 lag stiffened | static residual
    1   | 1.8e-2        | 1.8e-2            | 5.1e-3         | 6.5e-3             | 1.4e-2
    2   | 1.8e-2        | 1.9e-2            | 3.0e-4         | 6.1e-4             | 2.7e-3
    3   | 7.6e-3        | 8.3e-3            | 4.8e-5         | 1.3e-4             | 2.5e-3
    4   | 7.6e-3        | 8.2e-3            | 4.8e-5         | 1.3e-4             | 1.6e-4
    6   | 2.4e-3        | 2.3e-3            | 1.2e-5         | 1.4e-5             | 5.3e-5
    8   | 9.3e-4        | 9.3e-4            | 1.8e-6         | 6.0e-6             | 3.4e-5
    12  | 4.1e-4        | 4.4e-4            | 1.4e-6         | 4.1e-6             | 2.5e-6
    all | 2e-13         | 9e-13             | 6e-9           | 1.2e-8             | 1e-13

(stiffened: N modes + 6 axial coordinates.) Rotating plate (8 elements, R = 0,
beta = 90 deg, Omega = 3 sqrt(EI_y / (rho A L^4))), stiffened first flap frequency against
the nodal 1.33531 Hz: +2.0e-3 (N = 1), +3.1e-4 (2), +6.3e-5 (4), +2.5e-6 (8), +6.9e-7 (16).

So, for this plate: the tip motion of a released or slowly driven beam needs 3-4 modes
(the first two flap modes and the first chordwise one, 19.6 Hz) for 1e-2 of a strain near the
root and 1e-4 of the tip; about 8 modes (84 Hz) give 0.1 % of the root strain, which carries
the largest static share of the truncated modes. A load across the weak axis is missed
entirely until its first mode is kept: gravity in the width direction (beta = 0) needs N >= 4
(tip residual 100 % for N <= 3, 1.3 % for 4-8, 9e-4 for 12). Step loads excite every mode;
the kept ones miss the static share of the rest, which :func:`static_residual` measures; a load
or drive that changes over T seconds excites frequencies up to about 2 / T, which
``max_frequency_hz`` should exceed (:func:`coverage_warnings`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg import eigh

from hubbeam.elements.ffr.shape import NODE_DOFS
from hubbeam.numerics import coupled_groups

#: position of u0 among a node's six coordinates
_AXIAL = 0


def uncoupled_groups(stiffness: np.ndarray, mass: np.ndarray) -> list[np.ndarray]:
    """The groups of coordinates that no entry of K or M couples
    (:func:`~hubbeam.numerics.coupled_groups` of their entries that are not zero), each
    ascending, in the order of their first coordinate: for a straight beam without pretwist,
    whose principal axes are the frame's, the axial coordinates u0, the bending ones along the
    section's y (v, v') and z (w, w') and the twist theta
    (:data:`~hubbeam.elements.ffr.shape.DOF_NAMES`); one group when pretwist or the sections
    couple them."""
    return coupled_groups((stiffness != 0.0) | (mass != 0.0))


def clamped_modes(stiffness: np.ndarray, mass: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` lowest modes of K p = w^2 M p: (w^2 ascending, M-normalised columns).
    Each column's largest component is made positive (a reproducible sign).

    Solved group by group of the coordinates K and M do not couple (:func:`uncoupled_groups`),
    so that a mode is exactly zero outside its group: a mode bending along z has no component
    along y, in twist or stretch. Solved whole, such a mode carried round-off there (up to 1e-10
    of its largest component on exp1's plate), which filled every table the basis maps (the
    drag's centre-line rows, II) with entries the compiled kernels then summed. Frequencies of
    two groups equal to 1e-9 (a square section's bending along y and z) come in the groups'
    order (y before z), not in the order their round-off happens to give."""
    w2, columns = [], []
    for group in uncoupled_groups(stiffness, mass):
        kept = min(count, group.size)
        w2_g, phi_g = eigh(stiffness[np.ix_(group, group)], mass[np.ix_(group, group)], subset_by_index=[0, kept - 1])
        phi = np.zeros((stiffness.shape[0], kept))
        phi[group] = phi_g
        w2.append(w2_g)
        columns.append(phi)
    w2, phi = np.concatenate(w2), np.hstack(columns)
    order = np.argsort(w2, kind="stable")
    tie = np.zeros(order.size, dtype=np.int64)  # runs of frequencies equal to 1e-9, numbered
    for j in range(1, order.size):
        step = w2[order[j]] - w2[order[j - 1]] > 1e-9 * abs(w2[order[j - 1]])
        tie[j] = tie[j - 1] + step
    lowest = order[np.lexsort((order, tie))][:count]  # each run in the groups' order
    w2, phi = w2[lowest], phi[:, lowest]
    big = np.argmax(np.abs(phi), axis=0)
    return w2, phi * np.sign(phi[big, np.arange(phi.shape[1])])


def project(beam, basis: np.ndarray) -> None:
    """Map the nodal ``beam``'s invariants, stiffness and centre-line rows by p = basis @ eta,
    in place; rows built afterwards go through ``beam._scatter``, which applies the basis."""
    inv, B = beam.invariants, basis
    beam.invariants = {
        "m": inv["m"], "c0": inv["c0"], "I0": inv["I0"],
        "Sbar": inv["Sbar"] @ B,
        "J": inv["J"] @ B,
        "II": np.einsum("klfg,fa,gb->klab", inv["II"], B, B, optimize=True),
        "Mff": B.T @ inv["Mff"] @ B,
    }
    beam.stiffness_matrix = B.T @ beam.stiffness_matrix @ B
    beam._axial_stiffness = B.T @ beam._axial_stiffness @ B
    t = beam.centre_line_table
    beam.centre_line_table = {
        "N": t["N"] @ B, "x": t["x"], "w": t["w"], "b": t["b"],
        "mean_stretch": t["mean_stretch"] @ B,
        "mean_slope2": np.einsum("efg,fa,gb->eab", t["mean_slope2"], B, B, optimize=True),
    }
    beam.basis = B


def check_count(count, nodal_ndof: int) -> int:
    """``modes`` must be an integer from 1 to the nodal model's coordinates (6 per element)."""
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 1 <= count <= nodal_ndof:
        raise ValueError(f"modes: must be an integer from 1 to the nodal model's {nodal_ndof} coordinates "
                         f"(6 per element), got {count!r}")
    return int(count)


def reduce(beam, count: int, axial: str | None = None) -> None:
    """Make the nodal ``beam`` (just built) a modally reduced one, in place.

    ``axial``: "modal" (B = the ``count`` lowest modes) or "nodal" (B = the ``count`` lowest
    modes with u0 held, plus every nodal u0; at most the 5 per element there are); default
    "nodal" with geometric stiffening, "modal" without (see the module docstring). Sets
    ``basis``, ``mode_shapes`` (the modal columns, nodal ndof x kept) and ``frequencies_hz``
    (clamped, of the kept modes)."""
    n = beam.nodal_ndof
    count = check_count(count, n)
    K, M = beam.stiffness_matrix, beam.invariants["Mff"]
    if axial is None:
        axial = "nodal" if beam.geometric_stiffening else "modal"
    if axial == "modal":
        w2, phi = clamped_modes(K, M, count)
        basis = phi
    elif axial == "nodal":
        ax = np.arange(_AXIAL, n, NODE_DOFS)
        rest = np.setdiff1d(np.arange(n), ax)
        w2, sub = clamped_modes(K[np.ix_(rest, rest)], M[np.ix_(rest, rest)], min(count, rest.size))
        phi = np.zeros((n, sub.shape[1]))
        phi[rest] = sub
        E = np.zeros((n, ax.size))
        E[ax, np.arange(ax.size)] = 1.0
        basis = np.hstack([phi, E])
    else:
        raise ValueError(f"axial: 'modal' or 'nodal', got {axial!r}")
    beam.mode_shapes = phi
    beam.frequencies_hz = np.sqrt(np.maximum(w2, 0.0)) / (2.0 * np.pi)
    project(beam, basis)


# --------------------------------------------------------------------- coverage checks
@dataclass(frozen=True)
class StaticResidual:
    """What the kept modes miss of a static deflection p_s = K^-1 f of the nodal model: the
    reduced deflection is B (B^T K B)^-1 B^T f (the energy-norm projection of p_s).

    ``energy``: |p_s - p_r|_K / |p_s|_K; ``tip``: |u_tip(p_s) - u_tip(p_r)| / |u_tip(p_s)|
    (the tip centroid's displacement)."""

    energy: float
    tip: float


def static_residual(beam, load) -> StaticResidual:
    """The static-correction residual of a reduced ``beam`` under ``load``: a uniform
    acceleration (3,) in the body frame (e.g. gravity, ``A0.T @ g`` with A0 the clamped root
    frame, ``Mount.frame(theta)``) acting on the beam and its tip body, or a generalized force
    over the nodal coordinates (6 per element). Zero for a nodal beam."""
    if beam.basis is None:
        return StaticResidual(0.0, 0.0)
    nodal = replace(beam, modes=None)
    load = np.asarray(load, dtype=float)
    f = nodal.invariants["Sbar"].T @ load if load.shape == (3,) else load
    if f.shape != (nodal.ndof,):
        raise ValueError(f"load: a body-frame acceleration (3,) or a nodal force ({nodal.ndof},), got shape {load.shape}")
    K, B = nodal.stiffness_matrix, beam.basis
    p_s = np.linalg.solve(K, f)
    p_r = B @ np.linalg.solve(B.T @ K @ B, B.T @ f)
    d = p_s - p_r
    full = p_s @ K @ p_s
    tip = nodal.displacement_row(nodal.length)
    tip_s = np.linalg.norm(tip @ p_s)
    return StaticResidual(float(np.sqrt(max(d @ K @ d, 0.0) / full)) if full > 0 else 0.0,
                          float(np.linalg.norm(tip @ d) / tip_s) if tip_s > 0 else 0.0)


def coverage_warnings(beam, load=None, excitation_hz: float | None = None, tolerance: float = 0.01,
                      margin: float = 2.0, name: str = "beam", load_name: str = "gravity") -> list[str]:
    """One-line warnings for a reduced ``beam`` (none for a nodal one): when the tip deflection
    under ``load`` (see :func:`static_residual`) misses more than ``tolerance`` of its static
    value, and when ``excitation_hz`` (the highest frequency a run's loads or drive excite,
    about 2 / T for a change over T seconds) exceeds max_frequency_hz / ``margin``."""
    if beam.basis is None:
        return []
    out = []
    if load is not None and np.any(load):
        r = static_residual(beam, load)
        if r.tip > tolerance:
            out.append(f"{name}: the {beam.modes} kept modes miss {100 * r.tip:.2g} % of the static tip deflection "
                       f"under {load_name}; raise beam.modes")
    if excitation_hz is not None and excitation_hz * margin > beam.max_frequency_hz:
        out.append(f"{name}: the run excites up to about {excitation_hz:.3g} Hz but the highest kept mode is at "
                   f"{beam.max_frequency_hz:.3g} Hz; raise beam.modes")
    return out
