"""Loads along the span and in time: distributed force and moment per unit length, and tip
loads from time tables, on ANCF and FFR beams (the kind "span loads").

A :class:`SpanLoad` acts on one beam: at quadrature stations x_s along its span (m from the
root) it applies the force f(x_s, t) and the moment m(x_s, t) times a weight w_s (m; 1 for a
tip load, whose single station is x = L and whose values are N and N m). The values are linear
in time between the rows of a time table (held before the first and after the last) and, for
a table in x, linear in x between its stations; the stations are 3 Gauss points on every
piece between the element boundaries and the table's x values, so that the generalized force
of a piecewise linear force on the cubic shape functions is integrated exactly.

**Axes.** "global": the components are global and fixed in space (a dead load, as gravity).
"section": the components are on the root section frame [tau m n] of the beam (the clamped
root section: its mount's azimuth, radius, precone and twist, turning with the hub, the base
and joints), which does not follow the beam's deflection.

**Generalized forces** (virtual work f . delta r0(x) + m . delta omega(x), summed over the
stations). ANCF: the force on the positions and slopes through the Hermite functions (Eq.
32, as gravity), the moment through the section's virtual rotation at the station, which is
:func:`hubbeam.system.loads.tip_moment_terms` at the interpolated slope r0'(x_s) and twist
theta_1(x_s). FFR (v-space, as gravity and the tip loads in
:func:`hubbeam.elements.ffr.kernels.ffr_vspace_terms`): on r_C' the global force, on
omega^b r_b x f_b + m_b (r_b = (x, 0, 0) + N(x) p), on p N^T f_b + Phi^T m_b (f_b, m_b the
body-frame components), projected on the frame's coordinates by its Jacobians.

**Newton matrix.** In the time loop the loads add no entries (a load's dependence on the
coordinates is of the order of the load against the stiffness; Newton converges with the
matrix it has, in a few more iterations when that dependence is large).
With ``exact_stiffness`` (statics, modes, linearize) their stiffness is taken by central
differences of the generalized force over the columns it depends on.

**Energy.** A load's power sum_j Q_j x'_j is the drive power of this kind
(:mod:`hubbeam.system.terms`): the energy sensor counts its work in ``energy_drive``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.hermite import gauss_legendre, hermite
from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.beam import NODE_DOFS
from hubbeam.system.frame_motions import chain_columns
from hubbeam.system.frames import chain_kinematics
from hubbeam.system.loads import tip_moment_terms

#: quadrature points on each piece of the span (exact for a linear load on cubic shapes)
PIECE_GAUSS = 3
#: the columns of :attr:`SpanLoads.places`
INDEX, FORMULATION, X0, NQ, CHAIN, SECTION, STATIONS, TIMES, STIFF = range(9)
#: formulation codes in :attr:`SpanLoads.places`
ANCF, FFR = 0, 1
#: the element-vector offsets of r_a, r'_a, r_b, r'_b and of theta_a, theta'_a, theta_b, theta'_b
VECTOR_OFFSETS = (0, 3, NODE_DOFS, NODE_DOFS + 3)
ANGLE_OFFSETS = (6, 7, NODE_DOFS + 6, NODE_DOFS + 7)


@dataclass(eq=False)
class SpanLoad:
    """A load on beam ``beam`` (its place among the system's beams): at the stations x (m) with
    weights (m; 1 for point loads), the values (nt, ns, 6): force and moment components at each
    time of ``times`` (s), per unit length (N/m, N m/m) or, for point loads, N and N m; in
    global axes or, with ``section_axes``, on the root section frame (module docstring)."""

    beam: int
    stations: np.ndarray
    weights: np.ndarray
    times: np.ndarray
    values: np.ndarray
    section_axes: bool = False
    name: str = "span1"

    def __post_init__(self) -> None:
        self.stations = np.asarray(self.stations, dtype=float)
        self.weights = np.asarray(self.weights, dtype=float)
        self.times = np.atleast_1d(np.asarray(self.times, dtype=float))
        self.values = np.asarray(self.values, dtype=float).reshape(self.times.size, self.stations.size, 6)

    @classmethod
    def table(cls, beam: int, part, x, times, values, section_axes: bool = False, name: str = "span1") -> SpanLoad:
        """A distributed load given at the stations ``x`` (m, increasing, within [0, L] of ``part``,
        the beam's part) and ``times`` (s, increasing; one time: constant), ``values`` (nt, nx, 6)
        (N/m and N m/m), linear in x between the stations and zero outside [x_0, x_last]."""
        x = np.asarray(x, dtype=float)
        values = np.asarray(values, dtype=float).reshape(-1, x.size, 6)
        stations, weights = span_stations(part, x[0], x[-1], x)
        at = np.empty((values.shape[0], stations.size, 6))
        for r in range(values.shape[0]):
            for c in range(6):
                at[r, :, c] = np.interp(stations, x, values[r, :, c]) if x.size > 1 else values[r, 0, c]
        return cls(beam, stations, weights, times, at, section_axes, name)

    @classmethod
    def uniform(cls, beam: int, part, force, moment, section_axes: bool = False, name: str = "span1") -> SpanLoad:
        """A constant load per unit length over the whole span (N/m, N m/m)."""
        row = np.concatenate([np.asarray(force, dtype=float), np.asarray(moment, dtype=float)])
        return cls.table(beam, part, [0.0, part.length], [0.0], np.tile(row, (1, 2, 1)), section_axes, name)

    @classmethod
    def tip(cls, beam: int, part, times, force, moment, name: str = "tip") -> SpanLoad:
        """A tip force (N) and moment (N m), global, at the tip centroid, given at ``times`` (s):
        force and moment (nt, 3)."""
        times = np.atleast_1d(np.asarray(times, dtype=float))
        values = np.concatenate([np.asarray(force, dtype=float).reshape(-1, 3),
                                 np.asarray(moment, dtype=float).reshape(-1, 3)], axis=1)
        return cls(beam, [part.length], [1.0], times, values.reshape(times.size, 1, 6), False, name)


def span_stations(part, x_start: float, x_end: float, breaks=(), gauss: int = PIECE_GAUSS
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature stations and weights (m) on [x_start, x_end] of a beam part: ``gauss``
    Gauss points on every piece between its element boundaries and ``breaks``."""
    beam = part.beam
    nodes = np.linspace(0.0, part.length, beam.elements + 1)
    cuts = np.unique(np.concatenate([nodes, np.asarray(breaks, dtype=float), [x_start, x_end]]))
    cuts = cuts[(cuts >= x_start) & (cuts <= x_end)]
    xi, w = gauss_legendre(gauss)
    a, b = cuts[:-1], cuts[1:]
    keep = b - a > 1e-12 * part.length
    a, b = a[keep], b[keep]
    stations = (a[:, None] + (b - a)[:, None] * xi[None, :]).ravel()
    weights = ((b - a)[:, None] * w[None, :]).ravel()
    return stations, weights


class SpanLoads(NamedTuple):
    """Every span load of a system, one row each, zero-padded to the largest (padding stations
    have weight 0 and zero values; padding times repeat nothing: TIMES counts the real ones)."""

    places: np.ndarray  # int64 (nl, 9): INDEX (the beam's place among all beams), FORMULATION, X0 (its
    #                     coordinates in x), NQ (their number), CHAIN (its root section frame), SECTION (1:
    #                     section axes), STATIONS, TIMES, STIFF (1: the force depends on the coordinates)
    elements: np.ndarray  # int64 (nl, ns): ANCF: the element of each station
    S: np.ndarray  # (nl, ns, 4): ANCF: Hermite functions at the stations, and x-derivatives (1/m)
    dS: np.ndarray
    x: np.ndarray  # (nl, ns) stations (m)
    N: np.ndarray  # (nl, ns, 3, nf): FFR: displacement rows at the stations
    Phi: np.ndarray  # (nl, ns, 3, nf): FFR: small-rotation rows at the stations
    times: np.ndarray  # (nl, nt) s
    values: np.ndarray  # (nl, nt, ns, 6): weight times force and moment (N, N m)
    widest: int  # the largest number of columns a load acts on (frame's and the beam's)


def pack_span_loads(system, layout) -> SpanLoads | None:
    """The :class:`SpanLoads` of ``system`` (its attachments of this kind; None without any)."""
    loads = [a for a in system.attachments if isinstance(a, SpanLoad)]
    return pack_loads(system, layout, loads) if loads else None


def pack_loads(system, layout, loads) -> SpanLoads:
    """The :class:`SpanLoads` of the :class:`SpanLoad` s ``loads`` on the beams of ``system``
    placed by ``layout``."""
    from hubbeam.system.ancf_part import AncfPart

    nl = len(loads)
    ns = max(a.stations.size for a in loads)
    nt = max(a.times.size for a in loads)
    nf = max([system.beams[a.beam].ndof for a in loads])
    places = np.zeros((nl, 9), dtype=np.int64)
    elements = np.zeros((nl, ns), dtype=np.int64)
    S, dS = np.zeros((nl, ns, 4)), np.zeros((nl, ns, 4))
    x = np.zeros((nl, ns))
    N, Phi = np.zeros((nl, ns, 3, nf)), np.zeros((nl, ns, 3, nf))
    times = np.zeros((nl, nt))
    values = np.zeros((nl, nt, ns, 6))
    widest = 1
    for i, a in enumerate(loads):
        part = system.beams[a.beam]
        ancf = isinstance(part, AncfPart)
        chain = system.frames.root(a.beam)
        moments = bool(np.any(a.values[:, :, 3:6]))
        stiff = (not ancf) or a.section_axes or moments
        places[i] = (a.beam, ANCF if ancf else FFR, layout.beam_x(a.beam).start, part.ndof, chain,
                     int(a.section_axes), a.stations.size, a.times.size, int(stiff))
        n = a.stations.size
        x[i, :n] = a.stations
        times[i, :a.times.size] = a.times
        values[i, :a.times.size, :n] = a.values * a.weights[None, :, None]
        if ancf:
            located = [part.beam.locate(s) for s in a.stations]
            elements[i, :n] = [e for e, _ in located]
            hS, hdS, _ = hermite(np.array([xi for _, xi in located]), part.beam.element_length)
            S[i, :n], dS[i, :n] = hS, hdS
        else:
            for s, station in enumerate(a.stations):
                N[i, s, :, :part.ndof] = part.beam.displacement_row(station)
                Phi[i, s, :, :part.ndof] = part.beam.rotation_row(station)
        widest = max(widest, part.ndof + len(system.frames.chain(chain).coordinates))
    return SpanLoads(places, elements, S, dS, x, N, Phi, times, values, widest)


@njit(cache=True)
def interpolated_values(pack, i, t, out):
    """out (ns, 6) = load i's station values (N, N m) at time t: linear between the rows of its
    time table, held outside it."""
    nt = pack.places[i, TIMES]
    ns = pack.places[i, STATIONS]
    tt = pack.times[i]
    vals = pack.values[i]
    if nt == 1 or t <= tt[0]:
        lo, hi, s = 0, 0, 0.0
    elif t >= tt[nt - 1]:
        lo, hi, s = nt - 1, nt - 1, 0.0
    else:
        hi = 1
        while tt[hi] < t:
            hi += 1
        lo = hi - 1
        s = (t - tt[lo]) / (tt[hi] - tt[lo])
    for k in range(ns):
        for c in range(6):
            out[k, c] = (1.0 - s) * vals[lo, k, c] + s * vals[hi, k, c]


@njit(cache=True)
def load_force(pack, ctx, F, i, x, t, factor, cols, Q):
    """``factor`` times load i's generalized force (module docstring) at (t, x) on the x columns
    it acts on, written into cols[:m] and Q[:m]; returns m. The frame is evaluated at x."""
    pl = pack.places[i]
    x0, nq, ns = pl[X0], pl[NQ], pl[STATIONS]
    section = pl[SECTION] == 1
    ffr = pl[FORMULATION] == FFR
    frame_cols = chain_columns(ctx.chains, pl[CHAIN])
    nc = frame_cols.shape[0]
    r, R = np.empty(3), np.empty((3, 3))
    Jr, Jw = np.empty((3, nc)), np.empty((3, nc))
    chain_kinematics(ctx.chains, pl[CHAIN], x, F, 1, r, R, Jr, Jw, np.empty((3, nc, nc)), np.empty((3, nc, nc)))
    values = np.empty((ns, 6))
    interpolated_values(pack, i, t, values)
    used = nc if (ffr or section) else 0
    m = used + nq
    for j in range(used):
        cols[j] = frame_cols[j]
    for j in range(nq):
        cols[used + j] = x0 + j
    for j in range(m):
        Q[j] = 0.0
    fg, mg, fb, mb = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    for s in range(ns):
        for a in range(3):
            f_a, m_a = factor * values[s, a], factor * values[s, 3 + a]
            fg[a], mg[a], fb[a], mb[a] = f_a, m_a, f_a, m_a
        # the other axes: global = R section, section = R^T global
        for a in range(3):
            if section:
                fg[a] = R[a, 0] * fb[0] + R[a, 1] * fb[1] + R[a, 2] * fb[2]
                mg[a] = R[a, 0] * mb[0] + R[a, 1] * mb[1] + R[a, 2] * mb[2]
            else:
                fb[a] = R[0, a] * fg[0] + R[1, a] * fg[1] + R[2, a] * fg[2]
                mb[a] = R[0, a] * mg[0] + R[1, a] * mg[1] + R[2, a] * mg[2]
        if ffr:
            _ffr_station(pack, i, s, x[x0:x0 + nq], R, Jr, Jw, nc, fg, fb, mb, Q)
        else:
            _ancf_station(pack, i, s, x[x0:x0 + nq], F[pl[INDEX]], used, fg, mg, Q)
    return m


@njit(cache=True)
def _ancf_station(pack, i, s, q, chart, off, fg, mg, Q):
    """Station s of ANCF load i: the global force fg on the element's positions and slopes, the
    global moment mg through the section's virtual rotation (Q from index ``off``)."""
    base = off + NODE_DOFS * pack.elements[i, s]
    S, dS = pack.S[i, s], pack.dS[i, s]
    for a in range(4):
        o = base + VECTOR_OFFSETS[a]
        for j in range(3):
            Q[o + j] += S[a] * fg[j]
    if mg[0] == 0.0 and mg[1] == 0.0 and mg[2] == 0.0:
        return
    u = np.zeros(3)
    qb = base - off
    for a in range(4):
        o = qb + VECTOR_OFFSETS[a]
        for j in range(3):
            u[j] += dS[a] * q[o + j]
    tQ, tJ = np.empty(4), np.empty((4, 3))
    tip_moment_terms(u, mg, chart, tQ, tJ)
    for a in range(4):
        o = base + VECTOR_OFFSETS[a]
        for j in range(3):
            Q[o + j] += dS[a] * tQ[j]
        Q[base + ANGLE_OFFSETS[a]] += S[a] * tQ[3]


@njit(cache=True)
def _ffr_station(pack, i, s, p, R, Jr, Jw, nc, fg, fb, mb, Q):
    """Station s of FFR load i: its v-space force projected on [c, p] (Q[:nc + nf])."""
    nf = p.shape[0]
    N, Phi = pack.N[i, s], pack.Phi[i, s]
    rb = np.zeros(3)
    rb[0] = pack.x[i, s]
    for a in range(3):
        for f in range(nf):
            rb[a] += N[a, f] * p[f]
    moment = np.empty(3)  # on omega^b: r_b x f_b + m_b
    moment[0] = rb[1] * fb[2] - rb[2] * fb[1] + mb[0]
    moment[1] = rb[2] * fb[0] - rb[0] * fb[2] + mb[1]
    moment[2] = rb[0] * fb[1] - rb[1] * fb[0] + mb[2]
    # on the frame's columns: Jr^T fg + (R^T Jw)^T moment = Jr^T fg + Jw^T (R moment)
    mg = np.empty(3)
    for a in range(3):
        mg[a] = R[a, 0] * moment[0] + R[a, 1] * moment[1] + R[a, 2] * moment[2]
    for j in range(nc):
        Q[j] += (Jr[0, j] * fg[0] + Jr[1, j] * fg[1] + Jr[2, j] * fg[2]
                 + Jw[0, j] * mg[0] + Jw[1, j] * mg[1] + Jw[2, j] * mg[2])
    for f in range(nf):
        Q[nc + f] += (N[0, f] * fb[0] + N[1, f] * fb[1] + N[2, f] * fb[2]
                      + Phi[0, f] * mb[0] + Phi[1, f] * mb[1] + Phi[2, f] * mb[2])


def span_load_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                        exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """Every span load's rows: -coef_k Q on the columns it acts on; with ``exact_stiffness`` the
    matrix -coef_k dQ/dx by central differences (module docstring)."""
    zx = ctx.z_of_x
    width = pack.widest
    cols, Q = np.empty(width, dtype=np.int64), np.empty(width)
    for i in range(pack.places.shape[0]):
        m = load_force(pack, ctx, F, i, x, t, load_factor, cols, Q)
        for j in range(m):
            res[zx[cols[j]]] -= coef_k * Q[j]
        if not (want_matrix and exact_stiffness and coef_k != 0.0 and pack.places[i, STIFF] == 1):
            continue
        xp = x.copy()
        cp = np.empty(width, dtype=np.int64)
        Qp, Qm = np.empty(width), np.empty(width)
        for j in range(m):
            c = cols[j]
            h = 1e-6 * max(1.0, abs(x[c]))
            xp[c] = x[c] + h
            load_force(pack, ctx, F, i, xp, t, load_factor, cp, Qp)
            xp[c] = x[c] - h
            load_force(pack, ctx, F, i, xp, t, load_factor, cp, Qm)
            xp[c] = x[c]
            for r in range(m):
                value = -coef_k * (Qp[r] - Qm[r]) / (2.0 * h)
                if value != 0.0:
                    add_entry(ab, brow, bcol, bb, ctx.ku, zx[cols[r]], zx[c], value)
    return 2.0, 0.0


def span_load_power(pack, ctx, F, t, x, v, lam):
    """The loads' power sum_j Q_j x'_j (W): the drive's work of the energy balance."""
    width = pack.widest
    cols, Q = np.empty(width, dtype=np.int64), np.empty(width)
    power = 0.0
    for i in range(pack.places.shape[0]):
        m = load_force(pack, ctx, F, i, x, t, 1.0, cols, Q)
        for j in range(m):
            power += Q[j] * v[cols[j]]
    return power


def span_load_bandwidth(system, layout) -> int:
    """Half-bandwidth the loads' stiffness entries need: an FFR beam's and an ANCF beam's own
    entries are within their kind's band; a section-axes load on an ANCF beam couples its
    coordinates to its frame's coordinates outside the border (a joint angle, a parent's tip):
    the spread of their z places. 1 otherwise."""
    from hubbeam.system.ancf_part import AncfPart

    width = 1
    zx = layout.z_of_x
    for a in system.attachments:
        if not (isinstance(a, SpanLoad) and a.section_axes and isinstance(system.beams[a.beam], AncfPart)):
            continue
        frame = [zx[c] for c in system.frames.chain(system.frames.root(a.beam)).coordinates if zx[c] >= layout.border]
        if frame:
            every = list(zx[layout.beam_x(a.beam)]) + frame
            width = max(width, max(every) - min(every))
    return width


KIND = terms.register(SpanLoads, pack_span_loads, span_load_equations, bandwidth=span_load_bandwidth,
                      drive_power=span_load_power)
