"""Compiled equations of one FFR body (:class:`hubbeam.system.ffr_part.FfrPart`), in v-space.

The body frame's origin r_C (the root A) and axes A0 are a frame of the system (its root
section's, :mod:`hubbeam.system.frames`); the body's rates are v = [r_C' (global), omega^b
(body axes), p'] with p the elastic coordinates. :func:`ffr_vspace_terms` computes the
equations of motion on v (Eqs. 65-72: M_v vdot - Q and M_v, the drag's velocity matrix and
the elastic tangent), as :meth:`FfrPart.vspace_forces <hubbeam.system.ffr_part.FfrPart.vspace_forces>`
does with numpy (the tests hold them equal); the system projects them on the frame's
coordinates and p. :func:`ffr_energies`, :func:`ffr_momentum` and
:func:`ffr_dissipated_power` take the same v-space state.

**Argument groups** (plain tuples of float64 arrays and floats, built by :func:`hubbeam.elements.ffr.constants.pack`):

    inv  = (m, c0 (3,), Sbar (3, nf), I0 (3, 3), J (3, 3, nf), II (start, column, value), Mff (nf, nf),
            K (nf, nf), EAl (n_el,), mean_stretch (n_el, nf), mean_slope2 (n_el, nf, nf), stiffening,
            C_struct (nf, nf), damped)
    tip  = (tip_force (3,), tip_moment (3,), tip_rows (3, nf), tip_rotation_rows (3, nf), length)
    drag = (N (npts, 3, nf), span (npts, 2), x (npts,), w (npts,), width (npts,), c1, c2)

m, length, c1, c2, stiffening and damped (0.0 or 1.0) are floats. K is the stiffness
of Eq. 61, or without its axial part when ``stiffening`` (the axial energy then uses the
element-mean strain with the element integrals EAl = int_e EA dx (N m),
:meth:`FfrBeam.elastic <hubbeam.elements.ffr.body.FfrBeam.elastic>`). C_struct = c K (N s) is
the structural damping (Kelvin-Voigt on the material stiffness, :attr:`FfrBeam.damping_matrix
<hubbeam.elements.ffr.body.FfrBeam.damping_matrix>`), read when ``damped``; width is the drag's
frontal width at each centre-line point (m). II, the integrals int rho N_k^T N_l dV (3, 3, nf,
nf), is given by its entries that are not zero (:func:`sparse_entries`: compressed rows (k, l,
g), columns f, start (9 nf + 1,) and column (nnz,) int64), and span[k] = (first, last + 1) of the
coordinates f where N[k, :, f] is not zero (:func:`point_spans`, int64): a nodal beam's element
touches only its own nodes.
nf is taken from p (nf = p.shape[0]): the arrays may be larger (zero-padded, for
stacking beams of different meshes); only their leading nf entries are read, and padded
elements (zero rows of mean_stretch / mean_slope2) or Gauss points (zero weights) add
nothing.

The kernels use three properties of the arrays as FfrBeam builds them: II[k, l, f, g] =
II[l, k, g, f] to rounding (so one contraction of II with p serves both of its last indices); each
mean_slope2[e] is a sum of outer products (a zero diagonal entry means a zero row: element e
only touches the coordinates with a nonzero diagonal or mean_stretch entry); the drag's
N[k] rows vanish outside the point's element (the drag reads only the point's span, the damping
matrix skips zero columns). The drag's loops over the points are :mod:`hubbeam.elements.ffr.drag`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ffr.drag import drag_loop, drag_matrix


# ---------------------------------------------------------------------------- shared pieces
@njit(cache=True, error_model="numpy", _nrt=False)
def _moments(c0, Sbar, I0, J, II, p, pd, with_rate, nf, St, Q2, Q2d, R2):
    """St = c0 + Sbar p; Q2[k, l, g] = sum_f p_f II[k, l, f, g] (and, when ``with_rate``,
    Q2d the same with p' for k != l: the terms of Q_v read only those; Q2d[k, k] is left
    unwritten); R2 = I0 + J p + (J p)^T + p II p (the second moment, body frame; 9
    entries, row-major).
    II = (start, column, value), its entries that are not zero by rows (k, l, g), columns f
    (:func:`sparse_entries`): a nodal beam's II holds about 6 % of its (3, 3, nf, nf) entries
    (an element couples only its own nodes: 688 of 11664 on exp1's 6 elements), and the dense
    contraction was half of a nodal residual. Each Q2[k, l, g] is one row's sum in a register
    (no scattered stores: a modal beam's full rows cost what the dense loops did), its terms
    in the order of the dense loops, f rising from 0.0 (the same numbers to the last bit).
    II is symmetric as built, II[k, l, f, g] = II[l, k, g, f] (to rounding: the built entries
    differ in their last bits), so Q2 also gives the contractions on
    the last index: sum_g II[k, l, f, g] p_g = Q2[l, k, f] (to rounding). (c0, Sbar, I0, J,
    II: the invariants of the module docstring.)"""
    for k in range(3):
        acc = 0.0
        for f in range(nf):
            acc += Sbar[k, f] * p[f]
        St[k] = c0[k] + acc
    start, column, value = II
    if start[9 * nf] == 9 * nf * nf:  # every entry: row r's are f = 0, ..., nf - 1 at r nf (a modal beam)
        _dense_moments(value, p, pd, with_rate, nf, Q2, Q2d)
    else:
        _sparse_moments(start, column, value, p, pd, with_rate, nf, Q2, Q2d)
    for k in range(3):
        for l in range(3):
            jkl = 0.0  # (J p)[k, l] and (J p)[l, k]
            jlk = 0.0
            acc = 0.0
            for f in range(nf):
                jkl += J[k, l, f] * p[f]
                jlk += J[l, k, f] * p[f]
                acc += Q2[k, l, f] * p[f]
            R2[3 * k + l] = I0[k, l] + jkl + jlk + acc


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _dense_moments(value, p, pd, with_rate, nf, Q2, Q2d):
    """Q2 (and Q2d) of :func:`_moments` where II holds every entry (value[r nf + f] = II's row r,
    column f): the same sums, term for term, without the column indices (a modal beam's II is
    dense; measured on case R's 4 modes, python benchmarks/residual_pieces.py R: 0.26 -> 0.15 us a call)."""
    for k in range(3):
        for l in range(3):
            rate = with_rate and k != l
            row = (3 * k + l) * nf
            for g in range(nf):
                base = (row + g) * nf
                acc = 0.0
                if rate:
                    acc_rate = 0.0
                    for f in range(nf):
                        acc += p[f] * value[base + f]
                        acc_rate += pd[f] * value[base + f]
                    Q2d[k, l, g] = acc_rate
                else:
                    for f in range(nf):
                        acc += p[f] * value[base + f]
                Q2[k, l, g] = acc


@njit(cache=True, error_model="numpy", _nrt=False, inline="always")
def _sparse_moments(start, column, value, p, pd, with_rate, nf, Q2, Q2d):
    """Q2 (and Q2d) of :func:`_moments` from II's entries that are not zero (:func:`sparse_entries`)."""
    for k in range(3):
        for l in range(3):
            rate = with_rate and k != l
            row = (3 * k + l) * nf
            for g in range(nf):
                acc = 0.0
                if rate:
                    acc_rate = 0.0
                    for e in range(start[row + g], start[row + g + 1]):
                        f = column[e]
                        acc += p[f] * value[e]
                        acc_rate += pd[f] * value[e]
                    Q2d[k, l, g] = acc_rate
                else:
                    for e in range(start[row + g], start[row + g + 1]):
                        acc += p[column[e]] * value[e]
                Q2[k, l, g] = acc


def sparse_entries(II: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The entries of II (3, 3, nf, nf) that are not zero, as :func:`_moments` takes them, by
    rows r = (3 k + l) nf + g, columns f (compressed sparse rows of II[k, l, :, g]): (start (9
    nf + 1,) int64, the entries of row r being start[r]:start[r + 1]; column (nnz,) int64: their
    f; value (nnz,)), ordered by (k, l, g, f)."""
    nf = II.shape[2]
    rows = np.ascontiguousarray(np.swapaxes(II, 2, 3), dtype=np.float64).reshape(9 * nf, II.shape[2])
    r, f = np.nonzero(rows)
    start = np.zeros(9 * nf + 1, dtype=np.int64)
    start[1:] = np.cumsum(np.bincount(r, minlength=9 * nf))
    return start, f.astype(np.int64), np.ascontiguousarray(rows[r, f])


@njit(cache=True, error_model="numpy", _nrt=False)
def _elastic(K, EAl, a, G, stiff, p, nf, want_tangent, f_el, K_el, deps, act):
    """Internal force f_el (nf) and (when ``want_tangent``) tangent K_el (nf, nf) of
    :meth:`FfrBeam.elastic <hubbeam.elements.ffr.body.FfrBeam.elastic>` (K, EAl, a =
    mean_stretch, G = mean_slope2, stiff = stiffening: see the module docstring); deps (float)
    and act (int) scratch of nf entries."""
    for i in range(nf):
        acc = 0.0
        for j in range(nf):
            acc += K[i, j] * p[j]
        f_el[i] = acc
    if want_tangent:
        for i in range(nf):
            for j in range(nf):
                K_el[i, j] = K[i, j]
    if stiff == 0.0:
        return
    # element e only touches its own coordinates: those with a_e != 0 or (G_e)_ff != 0
    # (G_e is a sum of outer products, so a zero diagonal entry means a zero row)
    for e in range(a.shape[0]):
        na = 0
        for f in range(nf):
            if G[e, f, f] != 0.0 or a[e, f] != 0.0:
                act[na] = f
                na += 1
        eps = 0.0
        quad = 0.0
        for i in range(na):
            f = act[i]
            acc = 0.0
            for j in range(na):
                acc += G[e, f, act[j]] * p[act[j]]
            deps[f] = a[e, f] + acc
            eps += a[e, f] * p[f]
            quad += acc * p[f]
        eps += 0.5 * quad
        for i in range(na):
            f = act[i]
            f_el[f] += EAl[e] * deps[f] * eps
        if want_tangent:
            for i in range(na):
                f = act[i]
                for j in range(na):
                    g = act[j]
                    K_el[f, g] += EAl[e] * (deps[f] * deps[g] + eps * G[e, f, g])


@njit(cache=True, error_model="numpy", _nrt=False)
def tip_lever(T, length, p):
    """The tip point in the body frame, (L, 0, 0) + T p (m, a 3-tuple; T the tip's displacement
    rows over p, 3 x nf): the lever arm of the tip force, and the tip centroid's place on the body."""
    r0 = length
    r1 = 0.0
    r2 = 0.0
    for f in range(p.shape[0]):
        pf = p[f]
        r0 += T[0, f] * pf
        r1 += T[1, f] * pf
        r2 += T[2, f] * pf
    return r0, r1, r2


@njit(cache=True, error_model="numpy", _nrt=False)
def _applied_loads(m, Sbar, F, Mo, T, R, length, nf, A, St, p, gravity, factor, out):
    """out += factor (Q_g + Q_tip) (6 + nf, on v; Eq. 67 and FfrPart._tip_load): m, Sbar the
    invariants, F, Mo, T, R, length the ``tip`` group of the module docstring. The tip force
    acts at the deformed tip point (:func:`tip_lever`)."""
    g0, g1, g2 = gravity[0], gravity[1], gravity[2]
    F0, F1, F2 = F[0], F[1], F[2]
    M0, M1, M2 = Mo[0], Mo[1], Mo[2]
    # gravity, tip force and tip moment in the body frame (A0^T g etc.)
    gb0 = A[0, 0] * g0 + A[1, 0] * g1 + A[2, 0] * g2
    gb1 = A[0, 1] * g0 + A[1, 1] * g1 + A[2, 1] * g2
    gb2 = A[0, 2] * g0 + A[1, 2] * g1 + A[2, 2] * g2
    fb0 = A[0, 0] * F0 + A[1, 0] * F1 + A[2, 0] * F2
    fb1 = A[0, 1] * F0 + A[1, 1] * F1 + A[2, 1] * F2
    fb2 = A[0, 2] * F0 + A[1, 2] * F1 + A[2, 2] * F2
    mb0 = A[0, 0] * M0 + A[1, 0] * M1 + A[2, 0] * M2
    mb1 = A[0, 1] * M0 + A[1, 1] * M1 + A[2, 1] * M2
    mb2 = A[0, 2] * M0 + A[1, 2] * M1 + A[2, 2] * M2
    out[0] += factor * (m * g0 + F0)
    out[1] += factor * (m * g1 + F1)
    out[2] += factor * (m * g2 + F2)
    r0, r1, r2 = tip_lever(T, length, p)
    # St x gb + r x fb + mb
    out[3] += factor * (St[1] * gb2 - St[2] * gb1 + r1 * fb2 - r2 * fb1 + mb0)
    out[4] += factor * (St[2] * gb0 - St[0] * gb2 + r2 * fb0 - r0 * fb2 + mb1)
    out[5] += factor * (St[0] * gb1 - St[1] * gb0 + r0 * fb1 - r1 * fb0 + mb2)
    for f in range(nf):
        out[6 + f] += factor * (Sbar[0, f] * gb0 + Sbar[1, f] * gb1 + Sbar[2, f] * gb2
                                + T[0, f] * fb0 + T[1, f] * fb1 + T[2, f] * fb2
                                + R[0, f] * mb0 + R[1, f] * mb1 + R[2, f] * mb2)


@njit(cache=True, error_model="numpy")
def tip_load_power(tip, A, p, vb):
    """The power (W) of the beam's tip force and tip moment, Q_tip . vb: their generalized force
    on v (:func:`_applied_loads` without gravity, whose work is the potential energy) times the
    v-space rates vb = [r_C', omega^b, p']; ``tip`` the group of the module docstring, A the body
    frame, p the elastic coordinates."""
    F, Mo, T, R, length = tip
    nf = p.shape[0]
    Q = np.zeros(6 + nf)
    zero = np.zeros(3)
    _applied_loads(0.0, T, F, Mo, T, R, length, nf, A, zero, p, zero, 1.0, Q)
    power = 0.0
    for i in range(6 + nf):
        power += Q[i] * vb[i]
    return power


@njit(cache=True, error_model="numpy", _nrt=False)
def _mass_matrix(m, Sbar, J, Mff, nf, A, St, Q2, R2, Mv):
    """M_v of Eq. 66 (6 + nf square) on v."""
    n = 6 + nf
    for i in range(3):
        for j in range(3):
            Mv[i, j] = 0.0
        Mv[i, i] = m
    # M[0:3, 3:6] = -A0 skew(St), M[0:3, 6:] = A0 Sbar, and their transposes
    s0, s1, s2 = St[0], St[1], St[2]
    for a in range(3):
        a0, a1, a2 = A[a, 0], A[a, 1], A[a, 2]
        # row a of A0 skew(St): (a1 s2 - a2 s1, a2 s0 - a0 s2, a0 s1 - a1 s0)
        v0 = -(a1 * s2 - a2 * s1)
        v1 = -(a2 * s0 - a0 * s2)
        v2 = -(a0 * s1 - a1 * s0)
        Mv[a, 3], Mv[a, 4], Mv[a, 5] = v0, v1, v2
        Mv[3, a], Mv[4, a], Mv[5, a] = v0, v1, v2
        for f in range(nf):
            val = A[a, 0] * Sbar[0, f] + A[a, 1] * Sbar[1, f] + A[a, 2] * Sbar[2, f]
            Mv[a, 6 + f] = val
            Mv[6 + f, a] = val
    tr = R2[0] + R2[4] + R2[8]
    for i in range(3):
        for j in range(3):
            Mv[3 + i, 3 + j] = -R2[3 * i + j]
        Mv[3 + i, 3 + i] += tr
    # P = J + Q2; rows (P[1,2] - P[2,1], P[2,0] - P[0,2], P[0,1] - P[1,0])
    for f in range(nf):
        v0 = (J[1, 2, f] + Q2[1, 2, f]) - (J[2, 1, f] + Q2[2, 1, f])
        v1 = (J[2, 0, f] + Q2[2, 0, f]) - (J[0, 2, f] + Q2[0, 2, f])
        v2 = (J[0, 1, f] + Q2[0, 1, f]) - (J[1, 0, f] + Q2[1, 0, f])
        Mv[3, 6 + f] = v0
        Mv[4, 6 + f] = v1
        Mv[5, 6 + f] = v2
        Mv[6 + f, 3] = v0
        Mv[6 + f, 4] = v1
        Mv[6 + f, 5] = v2
    for f in range(nf):
        for g in range(nf):
            Mv[6 + f, 6 + g] = Mff[f, g]
    return n


# ---------------------------------------------------------------------------- the equations
@njit(cache=True, error_model="numpy", _nrt=False)
def ffr_dissipated_power(A, p, vb, Cs, damped, drag):
    """The power dissipated by the drag (Eq. 64) and the structural damping at the body frame
    A (3 x 3), the elastic coordinates p and the v-space rates vb = [r_C', omega^b, p']:
    -Q_d . vb + p'^T C_struct p' (W, >= 0): what :func:`ffr_vspace_terms` returns, without the
    body's other terms (for the energy balance after each step). Cs = C_struct and ``damped``
    of the invariants, ``drag`` the drag group (module docstring): only these, so that the
    caller builds no views of the other invariants."""
    power = 0.0
    nf = p.shape[0]
    pd = vb[6:6 + nf]
    if damped != 0.0:
        for f in range(nf):
            s = 0.0
            for g in range(nf):
                s += Cs[f, g] * pd[g]
            power += pd[f] * s
    Npts, span, xpts, wpts, width, dc1, dc2 = drag
    if dc1 == 0.0 and dc2 == 0.0:
        return power
    return power + drag_loop(Npts, span, xpts, wpts, width, dc1, dc2, p, pd, A, vb, vb, False)  # no force: vb unwritten


@njit(cache=True, error_model="numpy")
def _half_square(M, u, n):
    """u^T M u / 2 over the leading n entries."""
    total = 0.0
    for i in range(n):
        s = 0.0
        for j in range(n):
            s += M[i, j] * u[j]
        total += 0.5 * u[i] * s
    return total


@njit(cache=True, error_model="numpy")
def ffr_energies(inv, A, r_C, p, vb, gravity):
    """(kinetic, strain, gravity) energy of the FFR body (J) with its frame at r_C (m) and A
    (3 x 3), elastic coordinates p and v-space rates vb = [r_C', omega^b, p'] (a tip body is in
    the invariants): vb^T M_v vb / 2 (Eq. 66), the strain energy of :meth:`FfrBeam.elastic
    <hubbeam.elements.ffr.body.FfrBeam.elastic>` (p^T K p / 2, plus (int_e EA dx) eps_e^2 / 2
    per element with geometric stiffening) and -g . (m r_C + A0 S_t)."""
    nf = p.shape[0]
    n = 6 + nf
    St = np.empty(3)
    Q2 = np.empty((3, 3, nf))
    R2 = np.empty(9)
    _moments(inv[1], inv[2], inv[3], inv[4], inv[5], p, p, False, nf, St, Q2, Q2, R2)
    Mv = np.empty((n, n))
    _mass_matrix(inv[0], inv[2], inv[4], inv[6], nf, A, St, Q2, R2, Mv)
    kinetic = _half_square(Mv, vb, n)
    K, EAl, a, G, stiff = inv[7], inv[8], inv[9], inv[10], inv[11]
    strain = _half_square(K, p, nf)
    if stiff != 0.0:
        for e in range(a.shape[0]):
            eps = 0.0
            for f in range(nf):
                s = 0.0
                for g in range(nf):
                    s += G[e, f, g] * p[g]
                eps += (a[e, f] + 0.5 * s) * p[f]
            strain += 0.5 * EAl[e] * eps * eps
    potential = 0.0
    for i in range(3):
        potential -= gravity[i] * (inv[0] * r_C[i] + A[i, 0] * St[0] + A[i, 1] * St[1] + A[i, 2] * St[2])
    return kinetic, strain, potential


@njit(cache=True, error_model="numpy")
def ffr_momentum(inv, A, r_C, p, vb, out):
    """The body's mass, first moment and momenta added into out (10,) as
    :func:`hubbeam.system.terms.part_momenta` asks: the generalized momenta M_v vb conjugate to
    r_C' and omega^b are its linear momentum (global) and its angular momentum about r_C (body
    axes)."""
    nf = p.shape[0]
    n = 6 + nf
    St = np.empty(3)
    Q2 = np.empty((3, 3, nf))
    R2 = np.empty(9)
    _moments(inv[1], inv[2], inv[3], inv[4], inv[5], p, p, False, nf, St, Q2, Q2, R2)
    Mv = np.empty((n, n))
    _mass_matrix(inv[0], inv[2], inv[4], inv[6], nf, A, St, Q2, R2, Mv)
    mv = np.empty(6)
    for i in range(6):
        s = 0.0
        for j in range(n):
            s += Mv[i, j] * vb[j]
        mv[i] = s
    m = inv[0]
    out[0] += m
    for i in range(3):
        out[1 + i] += m * r_C[i] + A[i, 0] * St[0] + A[i, 1] * St[1] + A[i, 2] * St[2]
        out[4 + i] += mv[i]
    h = np.empty(3)  # angular momentum about r_C, global
    for i in range(3):
        h[i] = A[i, 0] * mv[3] + A[i, 1] * mv[4] + A[i, 2] * mv[5]
    out[7] += h[0] + r_C[1] * mv[2] - r_C[2] * mv[1]
    out[8] += h[1] + r_C[2] * mv[0] - r_C[0] * mv[2]
    out[9] += h[2] + r_C[0] * mv[1] - r_C[1] * mv[0]


@njit(cache=True, error_model="numpy", _nrt=False)
def ffr_vspace_terms(inv, A, p, vb, vdot, gravity, tip, drag, load_factor, want_matrix, fv, Mv, Cv, K_el, work,
                     elastic=True):
    """The FFR body's equations in v-space (v = [r_C', omega^b, p']): writes ``fv`` (6 + nf) =
    M_v vdot - Q, Q = Q_v + load_factor (Q_g + Q_tip) + Q_d - [0, 0, f_elastic + C_struct p']
    (Eqs. 65-72), and ``Mv`` = M_v (Eq. 66); when ``want_matrix`` also ``Cv`` = -dQ_d/dv (the
    drag's velocity matrix, zero without drag) and ``K_el`` (nf, nf) the elastic tangent with
    geometric stiffening. A (3 x 3) is the body frame (its axes the undeformed root section's),
    p the elastic coordinates, vb and vdot the v-space rates and accelerations; inv, tip, drag:
    the module docstring. The frame's own motion enters through vb and vdot alone: the caller
    projects on its coordinates (:mod:`hubbeam.system.ffr_beams`). ``work``: scratch of
    :func:`kernel_work` for at least nf coordinates and the drag's points. ``elastic`` False
    leaves the elastic force out of fv (the exact stiffness then takes it from K_el, and
    differences only the rest). Returns the power dissipated by the drag and the structural
    damping, -Q_d . vb + p'^T C_struct p' (W).

    Compiled without numba's reference counting, as the kernels it calls on every residual
    (:func:`_moments`, :func:`_mass_matrix`, :func:`_applied_loads`, :func:`drag_loop`): they
    allocate nothing and return no array (a residual's allocations and reference counts were
    about a fifth of an FFR step's time on exp1 with 4 modes)."""
    Sbar, J = inv[2], inv[4]
    Npts, span, xpts, wpts, width, dc1, dc2 = drag
    Cs, damped = inv[12], inv[13]
    nf = p.shape[0]
    n = 6 + nf
    pd = vb[6:n]
    w0, w1, w2 = vb[3], vb[4], vb[5]

    # body moments and the mass matrix
    vectors, Q2s, squares, ints = work
    Q, f_el, St, Qd, R2 = vectors[0], vectors[1], vectors[2], vectors[3], vectors[6]
    Q2, Q2d = Q2s[0], Q2s[1]
    _moments(inv[1], Sbar, inv[3], J, inv[5], p, pd, True, nf, St, Q2, Q2d, R2)
    _mass_matrix(inv[0], inv[2], inv[4], inv[6], nf, A, St, Q2, R2, Mv)

    # Q_v (Eq. 67), with W = [omega^b]x and WW = W W as scalars (the same products as the
    # matrix forms, without their zero terms)
    ud0 = 0.0
    ud1 = 0.0
    ud2 = 0.0
    for f in range(nf):
        pdf = pd[f]
        ud0 += Sbar[0, f] * pdf
        ud1 += Sbar[1, f] * pdf
        ud2 += Sbar[2, f] * pdf
    WW00, WW01, WW02 = -w2 * w2 - w1 * w1, w1 * w0, w2 * w0
    WW10, WW11, WW12 = w0 * w1, -w2 * w2 - w0 * w0, w2 * w1
    WW20, WW21, WW22 = w0 * w2, w1 * w2, -w1 * w1 - w0 * w0
    # t = WW St + 2 W ud
    t0 = WW00 * St[0] + WW01 * St[1] + WW02 * St[2] + 2.0 * (-w2 * ud1 + w1 * ud2)
    t1 = WW10 * St[0] + WW11 * St[1] + WW12 * St[2] + 2.0 * (w2 * ud0 - w0 * ud2)
    t2 = WW20 * St[0] + WW21 * St[1] + WW22 * St[2] + 2.0 * (-w1 * ud0 + w0 * ud1)
    for i in range(3):
        Q[i] = -(A[i, 0] * t0 + A[i, 1] * t1 + A[i, 2] * t2)
    tr = R2[0] + R2[4] + R2[8]
    # I omega = tr(R2) omega - R2 omega
    Iw0 = tr * w0 - (R2[0] * w0 + R2[1] * w1 + R2[2] * w2)
    Iw1 = tr * w1 - (R2[3] * w0 + R2[4] * w1 + R2[5] * w2)
    Iw2 = tr * w2 - (R2[6] * w0 + R2[7] * w1 + R2[8] * w2)
    # G[j, k] = int rho r_j udot_k = sum_f (J[j, k, f] + Q2[j, k, f]) p'_f; needed: tr G and G^T omega
    trG = 0.0
    GTw0 = 0.0
    GTw1 = 0.0
    GTw2 = 0.0
    for j in range(3):
        for k in range(3):
            sj = 0.0
            sq = 0.0
            for f in range(nf):
                pdf = pd[f]
                sj += J[j, k, f] * pdf
                sq += Q2[j, k, f] * pdf
            G = sj + sq
            if j == k:
                trG += G
            wG = vb[3 + j] * G
            if k == 0:
                GTw0 += wG
            elif k == 1:
                GTw1 += wG
            else:
                GTw2 += wG
    Q[3] = 0.0 - 2.0 * (w0 * trG - GTw0) - (w1 * Iw2 - w2 * Iw1)
    Q[4] = 0.0 - 2.0 * (w1 * trG - GTw1) - (w2 * Iw0 - w0 * Iw2)
    Q[5] = 0.0 - 2.0 * (w2 * trG - GTw2) - (w0 * Iw1 - w1 * Iw0)
    # Q_v on p: -sum_kl WW_kl int rho N_kf r_l - 2 sum_kl W_kl int rho N_kf (N p')_l
    # (int rho N_kf r_l = J[l, k, f] + Q2[l, k, f]; W has zero diagonal)
    for f in range(nf):
        s = (WW00 * (J[0, 0, f] + Q2[0, 0, f]) + WW01 * (J[1, 0, f] + Q2[1, 0, f])
             + WW02 * (J[2, 0, f] + Q2[2, 0, f]) + WW10 * (J[0, 1, f] + Q2[0, 1, f])
             + WW11 * (J[1, 1, f] + Q2[1, 1, f]) + WW12 * (J[2, 1, f] + Q2[2, 1, f])
             + WW20 * (J[0, 2, f] + Q2[0, 2, f]) + WW21 * (J[1, 2, f] + Q2[1, 2, f])
             + WW22 * (J[2, 2, f] + Q2[2, 2, f]))
        s3 = (-w2 * Q2d[1, 0, f] + w1 * Q2d[2, 0, f] + w2 * Q2d[0, 1, f] - w0 * Q2d[2, 1, f]
              - w1 * Q2d[0, 2, f] + w0 * Q2d[1, 2, f])
        Q[6 + f] = -s - 2.0 * s3

    # applied loads, elastic force
    F, Mo, T, R, length = tip
    _applied_loads(inv[0], Sbar, F, Mo, T, R, length, nf, A, St, p, gravity, load_factor, Q)
    _elastic(inv[7], inv[8], inv[9], inv[10], inv[11], p, nf, want_matrix, f_el, K_el, vectors[4], ints[0, :nf])
    if elastic:
        for f in range(nf):
            Q[6 + f] -= f_el[f]
    # structural damping c K p'
    power = 0.0
    if damped != 0.0:
        for f in range(nf):
            s = 0.0
            for g in range(nf):
                s += Cs[f, g] * pd[g]
            Q[6 + f] -= s
            power += pd[f] * s

    if want_matrix:
        for i in range(n):
            for j in range(n):
                Cv[i, j] = 0.0

    # drag (Eq. 64) on the centre line
    if dc1 != 0.0 or dc2 != 0.0:
        power += drag_loop(Npts, span, xpts, wpts, width, dc1, dc2, p, pd, A, vb, Qd, True)
        for i in range(n):
            Q[i] += Qd[i]
        if want_matrix:
            drag_matrix(Npts, xpts, wpts, width, dc1, dc2, p, pd, A, vb, 1.0, Cv, squares[0, 0:4, 0:3],
                         squares[0, 4:7, :n], vectors[5], squares[1, :n, :n], ints[1, :n])

    for i in range(n):
        s = 0.0
        for j in range(n):
            s += Mv[i, j] * vdot[j]
        fv[i] = s - Q[i]
    return power


def kernel_work(nf: int, npts: int, vectors=None, squares=None, ints=None) -> tuple:
    """Scratch of :func:`ffr_vspace_terms` for up to nf elastic coordinates and npts drag points,
    so that it allocates nothing: (vectors (7, >= 9 + 3 npts + nf): Q, the elastic force, S_t,
    Q_d with the drag's points, the elastic force's and the drag matrix's scratch, the second
    moment (9); (2, 3, 3, nf): the contractions of II with p and p'; squares (2, >= n + 1, >= n):
    the drag matrix's point vectors and S_b, and its C_v; int (2, >= n)), n = 6 + nf. ``vectors``,
    ``squares``, ``ints``: arrays of those shapes to use (views of a pack's scratch), else new."""
    n = 6 + nf
    vectors = np.zeros((7, n + 3 + 3 * npts)) if vectors is None else vectors
    squares = np.zeros((2, n + 1, n)) if squares is None else squares
    ints = np.zeros((2, n), dtype=np.int64) if ints is None else ints
    return vectors, np.zeros((2, 3, 3, nf)), squares, ints
