"""The kind "FFR beams" (:data:`KIND`, :mod:`hubbeam.system.terms`): every FFR beam of a system
(:class:`hubbeam.system.ffr_part.FfrPart`) packed (:class:`FfrBeams`), and its compiled terms,
energies, powers, momenta and tips.

**Equations** (Eqs. 65-72). With the frame's origin r_C (the root A), axes A0, velocity
Jacobians Jr, Jw and velocity products h_r, h_w (:func:`~hubbeam.system.frame_motions.frame_motion`),
the body's v-space rates and accelerations are

    v    = [r_C', omega^b, p']              = H [c', p'],   H = [[Jr, 0], [A0^T Jw, 0], [0, I]]
    vdot = [Jr c'' + h_r, A0^T (Jw c'' + h_w), p'']

and its generalized force on [c, p] is H^T (M_v vdot - Q) with M_v and Q of
:func:`~hubbeam.elements.ffr.kernels.ffr_vspace_terms` (inertia, gravity, tip loads, drag,
elastic force with geometric stiffening, structural damping; a tip body in the inertia
invariants, :class:`hubbeam.elements.ffr.body.FfrBeam`). The dynamic iteration matrix is
coef_m H^T M_v H + coef_c (H^T C_v H + C_struct) + coef_k K_el (the inertia forces'
derivatives left out: O((omega h)^2) against the mass term, they only slow Newton). Statics
and modes ask for the exact stiffness (``exact_stiffness``): K_el (exact) plus central
differences of the rest of the beam's force over its columns [c, p] at fixed rates and
accelerations, which holds every load's, frame's and steady rotation's dependence (steady
rotation moves p at zero rate).

:meth:`FfrPart.vspace_forces <hubbeam.system.ffr_part.FfrPart.vspace_forces>` is their Python
reference: the same formulas in v-space written with numpy, which the tests hold the kernel against.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ffr.kernels import (ffr_dissipated_power, ffr_energies, ffr_momentum, ffr_vspace_terms,
                                          kernel_work, tip_lever, tip_load_power)
from hubbeam.elements.ffr.constants import pack as ffr_constants
from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.frame_motions import chain_columns, displacement_in_reference, frame_motion
from hubbeam.system.frames import chain_kinematics, chain_products, chain_state, contracted_products

#: the constants of :class:`hubbeam.elements.ffr.constants.FfrArrays` that :class:`FfrBeams` holds
#: in one array per group of equal shapes, each field in its slot (its place in the group) along
#: the axis after the beam's: every array of the pack costs its reference count each time compiled
#: code passes the model or the pack (measured: 11 more arrays, +0.5 us per step_powers on exp1)
FFR_GROUPS = {"scalars": ("m", "stiffening", "damped", "length"),
              "vectors": ("c0", "tip_force", "tip_moment"),
              "rows": ("Sbar", "tip_rows", "tip_rotation_rows"),
              "squares": ("Mff", "K", "C_struct"),
              "points": ("x_pts", "w_pts", "width")}
#: the constants of FfrArrays that FfrBeams holds one array each
FFR_SINGLE = ("I0", "J", "II_value", "EAl", "mean_stretch", "mean_slope2", "N_pts")
#: the integer tables of FfrArrays (II's entries' places, the drag points' spans), one array each
FFR_INTEGERS = ("II_start", "II_column", "N_span")
#: the columns of :attr:`FfrBeams.places`
INDEX, X0, NF = 0, 1, 2


class FfrBeams(NamedTuple):
    """The FFR beams' constants (:func:`hubbeam.elements.ffr.constants.pack`), one row per FFR
    beam, zero-padded to the largest beam (the kernels read the leading nf entries); fields of
    equal shape grouped (:data:`FFR_GROUPS`, slots as listed there; :func:`ffr_arguments`)."""

    places: np.ndarray  # int64 (nb, 3): the beam's place among all beams (INDEX), where p starts in x (X0),
    #                     its elastic coordinates (NF)
    chains: np.ndarray  # int64 (nb, 2): its root section frame's chain (the body frame) and its reference frame's
    scalars: np.ndarray  # (nb, 4): m (kg), stiffening, damped, length (m)
    vectors: np.ndarray  # (nb, 3, 3): c0, tip_force, tip_moment
    rows: np.ndarray  # (nb, 3, 3, nf): Sbar, tip_rows, tip_rotation_rows
    squares: np.ndarray  # (nb, 3, nf, nf): Mff, K, C_struct (structural damping c K, N s)
    points: np.ndarray  # (nb, 3, npts): x_pts, w_pts, width of the centre-line points
    I0: np.ndarray
    J: np.ndarray
    II_value: np.ndarray
    EAl: np.ndarray
    mean_stretch: np.ndarray
    mean_slope2: np.ndarray
    N_pts: np.ndarray
    II_start: np.ndarray  # int64 (nb, 9 nf + 1): II's rows (k, l, g) in II_column and II_value (sparse_entries)
    II_column: np.ndarray  # int64 (nb, nnz): each entry's f (zero-padded, beyond the last row's end)
    N_span: np.ndarray  # int64 (nb, npts, 2): the drag points' spans (zero-padded: empty)
    vectors_work: np.ndarray  # (15, W) scratch vectors (W >= L = 6 + the largest nf + the widest frame's columns;
    #                           rows 8: the kernel's, :func:`_kernel_work`)
    squares_work: np.ndarray  # (8, L + 1, L + 1) scratch matrices (6: the kernel's)
    rows_work: np.ndarray  # int64 (3, L) scratch z rows (row 0) and the kernel's (rows 1:)
    moments_work: np.ndarray  # (2, 3, 3, the largest nf): the kernel's (:func:`~hubbeam.elements.ffr.kernels.kernel_work`)


def _stacked(values, dtype=float) -> np.ndarray:
    """The arrays ``values`` (of equal ndim) along a new leading axis, zero-padded to the largest."""
    values = [np.asarray(v, dtype=dtype) for v in values]
    shape = tuple(np.max([v.shape for v in values], axis=0)) if values[0].ndim else ()
    stacked = np.zeros((len(values),) + shape, dtype=dtype)
    for i, v in enumerate(values):
        stacked[(i,) + tuple(slice(0, n) for n in v.shape)] = v
    return stacked


def pack_ffr_beams(system, layout) -> FfrBeams | None:
    """The :class:`FfrBeams` of ``system`` placed by ``layout``, stacked and zero-padded (None
    without FFR beams)."""
    ffr = [(k, b) for k, b in enumerate(system.beams) if isinstance(b, FfrPart)]
    if not ffr:
        return None
    packs = [ffr_constants(b) for _, b in ffr]
    fields = {group: _stacked([_stacked([getattr(p, name) for name in names]) for p in packs])
              for group, names in FFR_GROUPS.items()}
    fields.update({name: _stacked([getattr(p, name) for p in packs]) for name in FFR_SINGLE})
    fields.update({name: _stacked([getattr(p, name) for p in packs], np.int64) for name in FFR_INTEGERS})
    places = np.array([(k, layout.beam_x(k).start, b.beam.ndof) for k, b in ffr], dtype=np.int64).reshape(len(ffr), 3)
    chains = np.array([(system.frames.root(k), system.frames.reference(k)) for k, _ in ffr],
                      dtype=np.int64).reshape(len(ffr), 2)
    widest = max(len(system.frames.chain(c).coordinates) for c in chains[:, 0])
    size = 6 + max(b.beam.ndof for _, b in ffr) + widest
    nf = max(b.beam.ndof for _, b in ffr)
    vectors, squares = np.zeros((15, size + 3 + 3 * fields["points"].shape[2])), np.zeros((8, size + 1, size + 1))
    rows = np.zeros((3, size), dtype=np.int64)
    _, moments, _, _ = kernel_work(nf, fields["points"].shape[2], vectors[8:], squares[6:], rows[1:])
    return FfrBeams(places, chains, **fields, vectors_work=vectors, squares_work=squares, rows_work=rows,
                    moments_work=moments)


def ffr_bandwidth(system, layout) -> int:
    """Half-bandwidth an FFR beam's block needs: its elastic coordinates and its frame's
    coordinates outside the border (a joint angle, a parent's tip; the hub angle when the
    border is empty); 1 without FFR beams."""
    width = 1
    zx = layout.z_of_x
    for k, b in enumerate(system.beams):
        if not isinstance(b, FfrPart):
            continue
        own = list(zx[layout.beam_x(k)])
        frame = [zx[c] for c in system.frames.chain(system.frames.root(k)).coordinates if zx[c] >= layout.border]
        every = own + frame
        width = max(width, max(every) - min(every))
    return width


@njit(cache=True, inline="always")
def ffr_drag_arguments(pack, k, drag_c):
    """The drag group of FFR beam k for :mod:`hubbeam.elements.ffr.kernels` (``drag_c``: c1, c2 of Eq. 37)."""
    pts = pack.points
    return (pack.N_pts[k], pack.N_span[k], pts[k, 0], pts[k, 1], pts[k, 2], drag_c[0], drag_c[1])


@njit(cache=True, inline="always")
def ffr_arguments(pack, k, drag_c):
    """(inv, tip, drag) of FFR beam k for :mod:`hubbeam.elements.ffr.kernels` (``drag_c``: c1, c2 of Eq. 37).
    Each array is a view of the pack's (each costs its construction and reference count, about
    10 to 20 ns): callers that need only some groups build only those (:func:`ffr_drag_arguments`)."""
    sc, vec, rows, sq = pack.scalars, pack.vectors, pack.rows, pack.squares  # slots: FFR_GROUPS
    inv = (sc[k, 0], vec[k, 0], rows[k, 0], pack.I0[k], pack.J[k], (pack.II_start[k], pack.II_column[k], pack.II_value[k]), sq[k, 0],
           sq[k, 1], pack.EAl[k], pack.mean_stretch[k], pack.mean_slope2[k], sc[k, 1], sq[k, 2], sc[k, 2])
    tip = (vec[k, 1], vec[k, 2], rows[k, 1], rows[k, 2], sc[k, 3])
    return inv, tip, ffr_drag_arguments(pack, k, drag_c)


@njit(cache=True, inline="always")
def _kernel_work(pack):
    """The scratch of :func:`~hubbeam.elements.ffr.kernels.ffr_vspace_terms` in the pack's
    (:func:`~hubbeam.elements.ffr.kernels.kernel_work`): views of its scratch arrays, so that the
    pack holds one array more, not four (each array of the pack costs its reference count
    wherever compiled code passes the model)."""
    return pack.vectors_work[8:], pack.moments_work, pack.squares_work[6:], pack.rows_work[1:]


@njit(cache=True)
def _fresh_frame(ctx, F, chain, x, v):
    """(columns, r, R, Jr, Jw, products) of a chain evaluated at x and rates v (not the cached
    state: the differences of the exact stiffness move x; products: its velocity products
    h_r, h_w, :func:`~hubbeam.system.frames.evaluate_motion`)."""
    cols = chain_columns(ctx.chains, chain)
    nc = cols.shape[0]
    r, R = np.empty(3), np.empty((3, 3))
    Jr, Jw = np.empty((3, nc)), np.empty((3, nc))
    Hr, Hw = np.empty((3, nc, nc)), np.empty((3, nc, nc))
    chain_kinematics(ctx.chains, chain, x, F, 2, r, R, Jr, Jw, Hr, Hw)
    products = np.empty((2, 3))
    contracted_products(Hr, Hw, cols, v, products)
    return cols, r, R, Jr, Jw, products


@njit(cache=True, _nrt=False)
def _vspace_rates(R, Jr, Jw, products, cols, v, acc, x0, nf, motion, vb, vdot):
    """vb = H [c', p'] and vdot = H [c'', p''] + [h_r, A0^T h_w, 0] (module docstring);
    ``motion`` (4, 3) scratch."""
    frame_motion(Jr, Jw, products, cols, v, acc, motion[0], motion[1], motion[2], motion[3])
    for i in range(3):
        vb[i] = motion[0, i]
        vdot[i] = motion[2, i]
        vb[3 + i] = R[0, i] * motion[1, 0] + R[1, i] * motion[1, 1] + R[2, i] * motion[1, 2]
        vdot[3 + i] = R[0, i] * motion[3, 0] + R[1, i] * motion[3, 1] + R[2, i] * motion[3, 2]
    for f in range(nf):
        vb[6 + f] = v[x0 + f]
        vdot[6 + f] = acc[x0 + f]


@njit(cache=True, inline="always")
def ffr_beam_terms(pack, ctx, frame, k, x, v, acc, load_factor, want_matrix, force, H, Mv, Cv, K_el, elastic=True):
    """FFR beam k's generalized force on its columns [c (the frame's nc), p (nf)] into ``force``
    (nc + nf; module docstring) and, when ``want_matrix``, its projection H ((6 + nf) x (nc +
    nf)), M_v, C_v and K_el (:func:`ffr_vspace_terms`; ``elastic`` False leaves the
    elastic force out). ``frame`` = (columns, r, R, Jr, Jw, products): its frame at x, as the
    system evaluated it (:func:`~hubbeam.system.frames.chain_state`) or afresh
    (:func:`_fresh_frame`). Returns the dissipated power (W).

    Inlined into its callers (it allocates nothing and returns no array), so that the system's
    equations, which count no references, do not pass it the pack and the context: a compiled
    call of its own, handed their ~40 arrays field by field, cost about 0.3 us per FFR beam and
    residual on case R (``benchmarks/residual_pieces.py``), 0.5 us when it counted their references."""
    nf = pack.places[k, NF]
    x0 = pack.places[k, X0]
    n = 6 + nf
    cols, r, R, Jr, Jw, products = frame
    nc = cols.shape[0]
    p = x[x0:x0 + nf]
    vecs = pack.vectors_work
    vb, vdot, fv = vecs[0, :n], vecs[1, :n], vecs[2, :n]
    _vspace_rates(R, Jr, Jw, products, cols, v, acc, x0, nf, vecs[3:7, :3], vb, vdot)
    inv, tip, drag = ffr_arguments(pack, k, ctx.drag)
    power = ffr_vspace_terms(inv, R, p, vb, vdot, ctx.gravity, tip, drag, load_factor, want_matrix, fv, Mv, Cv, K_el,
                             _kernel_work(pack), elastic)
    # the force on c: the frame's rows of H, [Jr; A0^T Jw], times fv[0:6]
    for j in range(nc):
        s = 0.0
        for a in range(3):
            s += Jr[a, j] * fv[a]
        for a in range(3):
            s += (R[0, a] * Jw[0, j] + R[1, a] * Jw[1, j] + R[2, a] * Jw[2, j]) * fv[3 + a]
        force[j] = s
    for f in range(nf):
        force[nc + f] = fv[6 + f]
    if want_matrix:  # H itself only for the matrix (zeroing it cost a nodal residual (6 + nf)(nc + nf) stores)
        m = nc + nf
        for i in range(n):
            for j in range(m):
                H[i, j] = 0.0
        for j in range(nc):
            for a in range(3):
                H[a, j] = Jr[a, j]
                H[3 + a, j] = R[0, a] * Jw[0, j] + R[1, a] * Jw[1, j] + R[2, a] * Jw[2, j]
        for f in range(nf):
            H[6 + f, nc + f] = 1.0
    return power


@njit(cache=True, inline="always")
def _beam_scratch(pack, ctx, k, want_matrix):
    """(force, H, M_v, C_v, K_el) of FFR beam k in the pack's scratch (:func:`ffr_beam_terms`;
    C_v empty without the matrix)."""
    nf = pack.places[k, NF]
    n = 6 + nf
    m = ctx.chains.column_start[pack.chains[k, 0] + 1] - ctx.chains.column_start[pack.chains[k, 0]] + nf
    sq = pack.squares_work
    Cv = sq[2, :n, :n] if want_matrix else sq[2, :0, :0]
    return pack.vectors_work[7, :m], sq[0, :n, :m], sq[1, :n, :n], Cv, sq[3, :nf, :nf]


@njit(cache=True, inline="always")
def _beam_residual(pack, ctx, k, x, v, acc, load_factor, want_matrix, coef_k, res):
    """FFR beam k's rows of the residual, coef_k H^T (M_v vdot - Q) (:func:`ffr_beam_terms`, the
    pieces of its matrix left in the scratch of :func:`_beam_scratch`), its z rows into the
    pack's rows_work[0]. Returns its dissipated power (W). Inlined, as :func:`ffr_beam_terms`
    (a call of its own cost another 0.3 us on case R)."""
    zx = ctx.z_of_x
    nf = pack.places[k, NF]
    x0 = pack.places[k, X0]
    force, H, Mv, Cv, K_el = _beam_scratch(pack, ctx, k, want_matrix)
    cols, r, R, Jr, Jw, _, _ = chain_state(ctx.chains, pack.chains[k, 0])
    frame = (cols, r, R, Jr, Jw, chain_products(ctx.chains, pack.chains[k, 0]))
    nc = cols.shape[0]
    power = ffr_beam_terms(pack, ctx, frame, k, x, v, acc, load_factor, want_matrix, force, H, Mv, Cv, K_el)
    rows = pack.rows_work[0]
    for j in range(nc):
        rows[j] = zx[cols[j]]
    for f in range(nf):
        rows[nc + f] = zx[x0 + f]
    for j in range(nc + nf):
        res[rows[j]] += coef_k * force[j]
    return power


@njit(cache=True, _nrt=True)
def _difference_stiffness(pack, ctx, F, k, x, v, acc, load_factor, coef_k, block):
    """block += coef_k times the stiffness of everything in FFR beam k's force on [c, p] but the
    elastic force (K_el, exact, is in the block already), by central differences of the force
    over [c, p] at fixed rates and accelerations (statics and modes). A function of its own,
    with numba's reference counting (``_nrt=True`` explicitly: a callee inherits its caller's
    setting unless it sets its own): it allocates, and the system's equations count no
    references (:func:`~hubbeam.system.equations.system_equations`)."""
    nf = pack.places[k, NF]
    x0 = pack.places[k, X0]
    n = 6 + nf
    cols = chain_columns(ctx.chains, pack.chains[k, 0])
    nc = cols.shape[0]
    m = nc + nf
    xp = x.copy()
    fp, fm = np.empty(m), np.empty(m)
    H2 = np.empty((n, m))
    M2, C2, K2 = np.empty((n, n)), np.empty((0, 0)), np.empty((nf, nf))
    for j in range(m):
        c = cols[j] if j < nc else x0 + j - nc
        h = 1e-6 * max(1.0, abs(x[c]))
        xp[c] = x[c] + h
        ffr_beam_terms(pack, ctx, _fresh_frame(ctx, F, pack.chains[k, 0], xp, v), k, xp, v, acc, load_factor,
                       False, fp, H2, M2, C2, K2, False)
        xp[c] = x[c] - h
        ffr_beam_terms(pack, ctx, _fresh_frame(ctx, F, pack.chains[k, 0], xp, v), k, xp, v, acc, load_factor,
                       False, fm, H2, M2, C2, K2, False)
        xp[c] = x[c]
        for i in range(m):
            block[i, j] += coef_k * (fp[i] - fm[i]) / (2.0 * h)


def ffr_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                  want_matrix, res, ab, brow, bcol, bb):
    """Every FFR beam's rows (:mod:`hubbeam.system.terms`): H^T (M_v vdot - Q) on its frame's
    coordinates and its own; the matrix coef_m H^T M_v H + coef_c (H^T C_v H + C_struct) +
    coef_k K_el, or with ``exact_stiffness`` the stiffness by central differences of the force
    (statics and modes; :func:`_difference_stiffness`). Inlined into the system's equations,
    which count no references: it allocates nothing and takes no array from a call."""
    ku = ctx.ku
    power = 0.0
    places = pack.places
    for k in range(places.shape[0]):
        power += _beam_residual(pack, ctx, k, x, v, acc, load_factor, want_matrix, coef_k, res)
        if not want_matrix:
            continue
        nf = places[k, NF]
        n = 6 + nf
        cols = chain_state(ctx.chains, pack.chains[k, 0])[0]  # inlined: a view, no array from a call
        nc = cols.shape[0]
        m = nc + nf
        sq = pack.squares_work
        _, H, Mv, Cv, K_el = _beam_scratch(pack, ctx, k, want_matrix)
        rows = pack.rows_work[0, :m]
        # coef_m H^T M_v H + coef_c H^T C_v H = H^T W H, W = coef_m M_v + coef_c C_v, with H =
        # [[Hc, 0], [0, I]] (Hc = H[0:6, 0:nc], the frame's rows): B = W[:, 0:6] Hc, then the
        # blocks [[Hc^T B[0:6], Hc^T W[0:6, 6:]], [B[6:], W[6:, 6:]]]; the products with H's zero
        # blocks left out (the same sums, term for term: a nodal beam's matrix was two dense
        # (6 + nf)^2 (nc + nf) products)
        B = sq[4, :n, :nc]
        for i in range(n):
            for j in range(nc):
                s = 0.0
                for a in range(6):
                    s += (coef_m * Mv[i, a] + coef_c * Cv[i, a]) * H[a, j]
                B[i, j] = s
        block = sq[5, :m, :m]
        for i in range(nc):
            for j in range(nc):
                s = 0.0
                for a in range(6):
                    s += H[a, i] * B[a, j]
                block[i, j] = s
            for g in range(nf):
                s = 0.0
                for a in range(6):
                    s += H[a, i] * (coef_m * Mv[a, 6 + g] + coef_c * Cv[a, 6 + g])
                block[i, nc + g] = s
        for f in range(nf):
            for j in range(nc):
                block[nc + f, j] = B[6 + f, j]
            for g in range(nf):
                block[nc + f, nc + g] = coef_m * Mv[6 + f, 6 + g] + coef_c * Cv[6 + f, 6 + g]
        Cs = pack.squares[k, 2]
        damped = pack.scalars[k, 2] != 0.0
        for f in range(nf):
            for g in range(nf):
                block[nc + f, nc + g] += coef_k * K_el[f, g] + (coef_c * Cs[f, g] if damped else 0.0)
        if exact_stiffness and coef_k != 0.0:
            _difference_stiffness(pack, ctx, F, k, x, v, acc, load_factor, coef_k, block)
        for i in range(m):
            for j in range(m):
                if block[i, j] != 0.0:
                    add_entry(ab, brow, bcol, bb, ku, rows[i], rows[j], block[i, j])
    return 2.0, power


@njit(cache=True)
def _frame_rates(pack, ctx, k, x, v, F):
    """(r, R, vb) of FFR beam k: its body frame and v-space rates (scratch of the pack)."""
    nf = pack.places[k, NF]
    x0 = pack.places[k, X0]
    cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chains[k, 0])
    vecs = pack.vectors_work
    vb = vecs[0, :6 + nf]
    _vspace_rates(R, Jr, Jw, chain_products(ctx.chains, pack.chains[k, 0]), cols, v, v, x0, nf, vecs[3:7, :3], vb,
                  vecs[1, :6 + nf])
    return r, R, vb


@njit(cache=True, inline="always")
def _body_state(pack, ctx, k, x, v, F):
    """(inv, R, r, p, vb) of FFR beam k: its invariants (:func:`ffr_arguments`), body frame, elastic
    coordinates and v-space rates, as the energies and momenta take them."""
    x0 = pack.places[k, X0]
    r, R, vb = _frame_rates(pack, ctx, k, x, v, F)
    inv, _, _ = ffr_arguments(pack, k, ctx.drag)
    return inv, R, r, x[x0:x0 + pack.places[k, NF]], vb


def ffr_beam_energies(pack, ctx, F, x, v, beams):
    """Kinetic, strain and gravity energy of every FFR beam, tip body included (J)."""
    for k in range(pack.places.shape[0]):
        inv, R, r, p, vb = _body_state(pack, ctx, k, x, v, F)
        kinetic, strain, potential = ffr_energies(inv, R, r, p, vb, ctx.gravity)
        terms.add_beam_energy(beams, pack.places[k, INDEX], kinetic, strain, potential)
    return 0.0, 0.0, 0.0


def ffr_momenta(pack, ctx, F, x, v, out):
    """Every FFR beam's mass, first moment and momenta (:func:`~hubbeam.elements.ffr.kernels.ffr_momentum`)."""
    for k in range(pack.places.shape[0]):
        inv, R, r, p, vb = _body_state(pack, ctx, k, x, v, F)
        ffr_momentum(inv, R, r, p, vb, out)


@njit(cache=True, _nrt=False)
def _dissipated_power(pack, ctx, v, x):
    """Power of the drag of Eq. 37 and of the structural damping on every FFR beam (W), at the
    frames as the system evaluated them. Compiled without numba's reference counting (as
    :func:`ffr_beam_terms`)."""
    power = 0.0
    places = pack.places
    still = ctx.drag[0] == 0.0 and ctx.drag[1] == 0.0
    vecs = pack.vectors_work
    for k in range(places.shape[0]):
        if still and pack.scalars[k, 2] == 0.0:  # neither drag nor structural damping
            continue
        nf = places[k, NF]
        x0 = places[k, X0]
        cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chains[k, 0])
        vb = vecs[0, :6 + nf]
        _vspace_rates(R, Jr, Jw, chain_products(ctx.chains, pack.chains[k, 0]), cols, v, v, x0, nf, vecs[3:7, :3],
                      vb, vecs[1, :6 + nf])
        power += ffr_dissipated_power(R, x[x0:x0 + nf], vb, pack.squares[k, 2], pack.scalars[k, 2],
                                      ffr_drag_arguments(pack, k, ctx.drag))
    return power


def ffr_power(pack, ctx, F, x, v):
    """Power of the drag of Eq. 37 and of the structural damping on every FFR beam (W)."""
    return _dissipated_power(pack, ctx, v, x)


def ffr_drive_power(pack, ctx, F, t, x, v, lam):
    """The power of the constant tip force and tip moment on every FFR beam (W): the drive's
    work of the energy balance, as the loads along the span count theirs
    (:func:`hubbeam.system.span_loads.span_load_power`)."""
    power = 0.0
    places = pack.places
    vec = pack.vectors
    for k in range(places.shape[0]):
        loaded = False
        for i in range(3):
            if vec[k, 1, i] != 0.0 or vec[k, 2, i] != 0.0:  # slots of FFR_GROUPS["vectors"]: tip_force, tip_moment
                loaded = True
        if loaded:
            power += _tip_loads_power(pack, ctx, k, x, v, F)
    return power


@njit(cache=True, _nrt=True)
def _tip_loads_power(pack, ctx, k, x, v, F):
    """The power of FFR beam k's tip force and tip moment (W; :func:`ffr_drive_power`): a
    function of its own with reference counting (as :func:`_difference_stiffness`), as it
    takes arrays from its calls."""
    nf = pack.places[k, NF]
    x0 = pack.places[k, X0]
    r, R, vb = _frame_rates(pack, ctx, k, x, v, F)
    _, tip, _ = ffr_arguments(pack, k, ctx.drag)
    return tip_load_power(tip, R, x[x0:x0 + nf], vb)


def ffr_tips(pack, ctx, F, x, out):
    """Each FFR beam's tip centroid displacement along its reference frame's axes (m)."""
    tip_at = np.empty(3)
    places = pack.places
    for k in range(places.shape[0]):
        x0 = places[k, X0]
        cols, r, R, Jr, Jw, Hr, Hw = chain_state(ctx.chains, pack.chains[k, 0])
        length = pack.scalars[k, 3]
        local = tip_lever(pack.rows[k, 1], length, x[x0:x0 + places[k, NF]])
        for i in range(3):
            tip_at[i] = r[i] + R[i, 0] * local[0] + R[i, 1] * local[1] + R[i, 2] * local[2]
        displacement_in_reference(ctx, F, x, pack.chains[k, 0], pack.chains[k, 1], length, tip_at,
                                  out[places[k, INDEX]])


def ffr_powers_possible(pack: FfrBeams, ctx) -> bool:
    """Whether the FFR beams can have a power that is not zero (:func:`hubbeam.system.terms.with_powers`):
    the system's drag (Eq. 37) on them, a beam's structural damping, or a tip force or tip moment
    (the terms of :func:`ffr_power` and :func:`ffr_drive_power`)."""
    drag = ctx.drag[0] != 0.0 or ctx.drag[1] != 0.0
    scalar, vector = FFR_GROUPS["scalars"].index, FFR_GROUPS["vectors"].index
    damped = bool(np.any(pack.scalars[:, scalar("damped")] != 0.0))
    loaded = bool(np.any(pack.vectors[:, [vector("tip_force"), vector("tip_moment")]] != 0.0))
    return drag or damped or loaded


KIND = terms.register(FfrBeams, pack_ffr_beams, ffr_equations, ffr_beam_energies, ffr_power, ffr_tips,
                      bandwidth=ffr_bandwidth, drive_power=ffr_drive_power, momenta=ffr_momenta,
                      powers_possible=ffr_powers_possible, counts_references=False)
