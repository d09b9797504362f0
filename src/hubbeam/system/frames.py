"""Frames: where bodies and beam roots hang, as chains of elementary transforms.

A frame of a system (the base, the hub, a beam's root section, a rigid body's principal
axes at its centre of mass, ...) is a *chain*: the product of elementary transforms, each
either constant or moved by coordinates of the system:

    T = T_1 T_2 ... T_n,   T_i = (t_i, R_i): a point p of the next frame is at t_i + R_i p

- ``CONSTANT``: a fixed offset t and rotation R (a mount, the hub's place on the base, a
  twist);
- ``REVOLUTE``: a rotation by ``sign * c`` about a fixed unit axis of the current frame, c one
  coordinate (the hub angle theta turns about -j, ``sign = -1``; a joint angle psi);
- ``FREE`` (first link only): a rigid body's six degrees of freedom in seven coordinates,
  the position r_b (3) and the Euler parameters e = (e0, e1, e2, e3) (4) of its rotation
  R(e / |e|) (the rotation of the normalised parameters: it is exact for any e != 0, and the
  norm is fixed by a constraint elsewhere);
- ``ANCF_TIP`` (first link only): the section frame of an ANCF node, from its position r0
  (3), slope r0' (3) and twist theta_1 (1) in a rotation chart F (:mod:`hubbeam.elements.ancf.frame`);
- ``FFR_TIP``: the tip section of an FFR beam floating on the current frame, moved by its
  nf elastic coordinates p: a translation by (L, 0, 0) + N_L p and a small rotation by
  phi = Phi_L p (N_L, Phi_L: the tip's displacement and rotation rows of
  :class:`~hubbeam.elements.ffr.body.FfrBeam`), turned as successive rotations by phi_1, phi_2,
  phi_3 about the current x, y', z'' axes (equal to the rotation vector phi to first order,
  FFR's own kinematics).

For every coordinate c_i of a chain :func:`chain_kinematics` gives the frame's pose (r, R)
and the velocity Jacobians: Jw[:, i], the frame's angular velocity per unit c_i' (global
axes), and Jr[:, i], its origin's velocity; and, on request, their derivatives
Hw[:, i, l] = dJw[:, i] / dc_l and Hr[:, i, l] = dJr[:, i] / dc_l. For coordinates whose
motion is a fixed screw of the frame before them (revolute: axis u_i through o_i, so
Jw_i = u_i, Jr_i = u_i x (r - o_i); a translation: Jw_i = 0, Jr_i = a fixed direction) the
serial-chain rule gives them all by cross products:

    l before or equal i:  Hw_il = Jw_l x Jw_i,   Hr_il = Jw_l x Jr_i
    l after i:            Hw_il = 0,             Hr_il = Jw_i x Jr_l

(a translation along an axis of the current frame, Jw_i = 0 and Jr_i that axis, follows the
same rule). The first link's own coordinates (``FREE``, ``ANCF_TIP``) are not such screws among
each other: their mutual derivatives are written out below; with every later coordinate the
rule holds (the first link carries the rest of the chain). An ``FFR_TIP`` link is six such
screws in a row (three translations, three revolutes) whose *virtual* coordinates
v = M p, M = [N_L; Phi_L] (6 x nf), are linear in its nf coordinates: the Jacobians and
derivatives are computed over the virtual columns by the rule and then carried to the real
ones, J_p = J_v M, H_pp = M^T H_vv M, H_pc = M^T H_vc (exact: v is linear in p). Tests check
every Jacobian and derivative against finite differences of the pose.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit


class LinkKind(enum.IntEnum):
    """The elementary transforms of a chain (the members are what compiled code compares)."""

    CONSTANT = 0
    REVOLUTE = 1
    FREE = 2
    ANCF_TIP = 3
    FFR_TIP = 4


#: coordinates each link kind moves (an FFR tip: its beam's elastic coordinates, :attr:`Link.coordinates`)
LINK_COORDINATES = {LinkKind.CONSTANT: 0, LinkKind.REVOLUTE: 1, LinkKind.FREE: 7, LinkKind.ANCF_TIP: 7}
#: columns of a link row in :class:`ChainTable.links`
KIND, COORD, PARAM = 0, 1, 2
#: virtual columns of an FFR tip: translations along x, y, z, then rotations about x, y', z''
FFR_TIP_VIRTUAL = 6


@dataclass(frozen=True)
class Link:
    """One elementary transform. ``coordinate``: where its first coordinate sits in x (-1 for a
    constant link); ``offset`` (m) and ``rotation`` (3 x 3) of a constant link; ``axis`` (unit,
    in the current frame) and ``sign`` of a revolute one; ``chart``: the index in F of an ANCF
    tip's rotation chart."""

    kind: LinkKind
    coordinate: int = -1
    offset: tuple = (0.0, 0.0, 0.0)
    rotation: tuple = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    axis: tuple = (0.0, 1.0, 0.0)
    sign: float = 1.0
    chart: int = 0
    length: float = 0.0
    rows: tuple = ()

    @property
    def coordinates(self) -> int:
        if self.kind == LinkKind.FFR_TIP:
            return len(self.rows[0])
        return LINK_COORDINATES[self.kind]

    def params(self) -> np.ndarray:
        """The link's 13 numbers for compiled code: offset (3) and rotation (9, row-major) of a
        constant link; axis (3) and sign of a revolute one; the chart's index of an ANCF tip."""
        out = np.zeros(13)
        if self.kind == LinkKind.CONSTANT:
            out[0:3] = self.offset
            out[3:12] = np.asarray(self.rotation, dtype=float).ravel()
        elif self.kind == LinkKind.REVOLUTE:
            axis = np.asarray(self.axis, dtype=float)
            out[0:3] = axis / np.linalg.norm(axis)
            out[3] = self.sign
        elif self.kind == LinkKind.ANCF_TIP:
            out[0] = self.chart
        elif self.kind == LinkKind.FFR_TIP:  # the rows' place in ChainTable.maps is set by ChainTable.of
            out[0] = self.length
            out[2] = self.coordinates
        return out


def constant(offset=(0.0, 0.0, 0.0), rotation=None) -> Link:
    """A constant link: translate by ``offset`` (m, current frame), then turn by ``rotation``."""
    rot = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float)
    return Link(LinkKind.CONSTANT, offset=tuple(float(v) for v in offset),
                rotation=tuple(tuple(float(v) for v in row) for row in rot))


def revolute(coordinate: int, axis, sign: float = 1.0) -> Link:
    """A rotation by sign * x[coordinate] about ``axis`` (current frame)."""
    return Link(LinkKind.REVOLUTE, coordinate, axis=tuple(float(v) for v in axis), sign=float(sign))


def free(coordinate: int) -> Link:
    """A free rigid body: x[coordinate : coordinate + 7] = (r_b, e)."""
    return Link(LinkKind.FREE, coordinate)


def ancf_tip(coordinate: int, chart: int) -> Link:
    """The section frame of the ANCF node whose 8 coordinates start at x[coordinate], in chart F[chart]."""
    return Link(LinkKind.ANCF_TIP, coordinate, chart=chart)


def ffr_tip(coordinate: int, length: float, displacement_rows, rotation_rows) -> Link:
    """The tip section of an FFR beam of ``length`` (m) whose nf elastic coordinates p start at
    x[coordinate]: translated by (length, 0, 0) + N p and turned by phi = Phi p (module
    docstring); ``displacement_rows`` N (3 x nf), ``rotation_rows`` Phi (3 x nf)."""
    rows = np.vstack([np.asarray(displacement_rows, dtype=float), np.asarray(rotation_rows, dtype=float)])
    if rows.shape[0] != FFR_TIP_VIRTUAL or rows.shape[1] < 1:
        raise ValueError(f"an FFR tip needs 3 + 3 rows over its coordinates (got {rows.shape})")
    return Link(LinkKind.FFR_TIP, coordinate, length=float(length),
                rows=tuple(tuple(float(v) for v in r) for r in rows))


@dataclass(frozen=True)
class Chain:
    """A frame as a product of links (the first may be FREE or ANCF_TIP)."""

    links: tuple = field(default_factory=tuple)

    def __post_init__(self) -> None:
        for i, link in enumerate(self.links):
            if i > 0 and link.kind in (LinkKind.FREE, LinkKind.ANCF_TIP):
                raise ValueError(f"a {link.kind.name} link must be the first of its chain")
            if i == 0 and link.kind == LinkKind.FFR_TIP:
                raise ValueError("an FFR_TIP link hangs on the frame of its beam: it cannot be the first of its chain")

    def then(self, *links: Link) -> "Chain":
        """This chain continued by ``links``."""
        return Chain(self.links + tuple(links))

    @property
    def coordinates(self) -> list[int]:
        """x indices of the chain's coordinate columns, in chain order."""
        out = []
        for link in self.links:
            out += [link.coordinate + j for j in range(link.coordinates)]
        return out

    def pose(self, x, F=None) -> tuple[np.ndarray, np.ndarray]:
        """(r, R) at x (a Python convenience over :func:`chain_kinematics`)."""
        table = ChainTable.of([self])
        return chain_pose(table, 0, x, F)[:2]


class ChainTable(NamedTuple):
    """Every chain of a system in arrays for compiled code (:meth:`of`)."""

    links: np.ndarray  # int64 (n_links, 3): kind, first coordinate's x index, row in params
    params: np.ndarray  # (n_links, 13): Link.params
    start: np.ndarray  # int64 (n_chains + 1): chain k's links are links[start[k]:start[k + 1]]
    columns: np.ndarray  # int64 (n_columns,): the chains' coordinate columns' x indices
    column_start: np.ndarray  # int64 (n_chains + 1): chain k's columns are columns[column_start[k]:...]
    maps: np.ndarray  # (n,): the FFR tips' rows M (6 x nf, row-major), each from its link's params[1]

    @classmethod
    def of(cls, chains) -> "ChainTable":
        links, params, start, columns, cstart, maps = [], [], [0], [], [0], []
        for chain in chains:
            for link in chain.links:
                links.append((int(link.kind), link.coordinate, len(params)))
                row = link.params()
                if link.kind == LinkKind.FFR_TIP:
                    row[1] = len(maps)
                    maps += [v for r in link.rows for v in r]
                params.append(row)
            start.append(len(links))
            columns += chain.coordinates
            cstart.append(len(columns))
        ints = lambda v, shape: np.array(v, dtype=np.int64).reshape(shape)  # noqa: E731
        return cls(ints(links, (len(links), 3)), np.array(params, dtype=float).reshape(len(params), 13),
                   ints(start, (len(start),)), ints(columns, (len(columns),)), ints(cstart, (len(cstart),)),
                   np.array(maps, dtype=float))

    def width(self, k: int) -> int:
        """Number of coordinate columns of chain k."""
        return int(self.column_start[k + 1] - self.column_start[k])


# ---------------------------------------------------------------------------- small pieces
@njit(cache=True)
def cross_into(a, b, out):
    """out = a x b (3-vectors)."""
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@njit(cache=True)
def euler_rotation(e, R):
    """R = the rotation of the normalised Euler parameters e / |e| (columns: the body axes, global)."""
    e0, e1, e2, e3 = e[0], e[1], e[2], e[3]
    s = e0 * e0 + e1 * e1 + e2 * e2 + e3 * e3
    R[0, 0] = (e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3) / s
    R[1, 1] = (e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3) / s
    R[2, 2] = (e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3) / s
    R[0, 1] = 2.0 * (e1 * e2 - e0 * e3) / s
    R[1, 0] = 2.0 * (e1 * e2 + e0 * e3) / s
    R[0, 2] = 2.0 * (e1 * e3 + e0 * e2) / s
    R[2, 0] = 2.0 * (e1 * e3 - e0 * e2) / s
    R[1, 2] = 2.0 * (e2 * e3 - e0 * e1) / s
    R[2, 1] = 2.0 * (e2 * e3 + e0 * e1) / s


@njit(cache=True)
def euler_rate_matrix(e, E):
    """E (3 x 4) with the angular velocity (global axes) w = 2 E e' / (e . e) for any e != 0:
    E = [-v, e0 I + [v]x], v = (e1, e2, e3)."""
    e0, e1, e2, e3 = e[0], e[1], e[2], e[3]
    E[0, 0], E[0, 1], E[0, 2], E[0, 3] = -e1, e0, -e3, e2
    E[1, 0], E[1, 1], E[1, 2], E[1, 3] = -e2, e3, e0, -e1
    E[2, 0], E[2, 1], E[2, 2], E[2, 3] = -e3, -e2, e1, e0


@njit(cache=True)
def _rotate_about(R, axis, angle, out):
    """out = R Rot(axis, angle) (axis a unit vector of the frame R)."""
    c, s = math.cos(angle), math.sin(angle)
    a0, a1, a2 = axis[0], axis[1], axis[2]
    C = 1.0 - c
    Q = np.empty((3, 3))
    Q[0, 0] = c + a0 * a0 * C
    Q[0, 1] = a0 * a1 * C - a2 * s
    Q[0, 2] = a0 * a2 * C + a1 * s
    Q[1, 0] = a1 * a0 * C + a2 * s
    Q[1, 1] = c + a1 * a1 * C
    Q[1, 2] = a1 * a2 * C - a0 * s
    Q[2, 0] = a2 * a0 * C - a1 * s
    Q[2, 1] = a2 * a1 * C + a0 * s
    Q[2, 2] = c + a2 * a2 * C
    for i in range(3):
        for j in range(3):
            out[i, j] = R[i, 0] * Q[0, j] + R[i, 1] * Q[1, j] + R[i, 2] * Q[2, j]


@njit(cache=True)
def _ancf_section(F, u, phi, R):
    """The section frame R = F [tau m n](F^T u, phi) (global columns) of slope u and twist phi."""
    U = np.empty(3)
    for a in range(3):
        U[a] = F[0, a] * u[0] + F[1, a] * u[1] + F[2, a] * u[2]
    L = math.sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2])
    T0, T1, T2 = U[0] / L, U[1] / L, U[2] / L
    den = 1.0 + T0
    h1, h2 = T1 / den, T2 / den
    # m0, n0 (chart components) of the untwisted chart frame
    m00, m01, m02 = -h1 * (T0 + 1.0), 1.0 - h1 * T1, -h1 * T2
    n00, n01, n02 = -h2 * (T0 + 1.0), -h2 * T1, 1.0 - h2 * T2
    c, s = math.cos(phi), math.sin(phi)
    loc = np.empty((3, 3))
    loc[0, 0], loc[1, 0], loc[2, 0] = T0, T1, T2
    loc[0, 1], loc[1, 1], loc[2, 1] = c * m00 + s * n00, c * m01 + s * n01, c * m02 + s * n02
    loc[0, 2], loc[1, 2], loc[2, 2] = -s * m00 + c * n00, -s * m01 + c * n01, -s * m02 + c * n02
    for i in range(3):
        for j in range(3):
            R[i, j] = F[i, 0] * loc[0, j] + F[i, 1] * loc[1, j] + F[i, 2] * loc[2, j]
    return L


@njit(cache=True)
def _ancf_rate_columns(d, tau, L, y, out):
    """out = A y, the angular velocity of the chart's untwisted frame for the slope rate y:
    (tau x y - tau d.(tau x y) / (1 + d.tau)) / L."""
    cross_into(tau, y, out)
    k = (d[0] * out[0] + d[1] * out[1] + d[2] * out[2]) / (1.0 + d[0] * tau[0] + d[1] * tau[1] + d[2] * tau[2])
    for i in range(3):
        out[i] = (out[i] - tau[i] * k) / L


@njit(cache=True)
def _ancf_rate_derivative(d, tau, L, y, b, out):
    """out = d(A y)/d u_b (u = r0', y fixed): the derivative of :func:`_ancf_rate_columns` along
    the slope's component b."""
    dL = tau[b]
    t = np.empty(3)  # d tau / d u_b
    for i in range(3):
        t[i] = ((1.0 if i == b else 0.0) - tau[i] * tau[b]) / L
    den = 1.0 + d[0] * tau[0] + d[1] * tau[1] + d[2] * tau[2]
    ty = np.empty(3)
    cross_into(tau, y, ty)
    dty = np.empty(3)
    cross_into(t, y, dty)
    k = (d[0] * ty[0] + d[1] * ty[1] + d[2] * ty[2]) / den
    dk = (d[0] * dty[0] + d[1] * dty[1] + d[2] * dty[2]) / den \
        - k * (d[0] * t[0] + d[1] * t[1] + d[2] * t[2]) / den
    for i in range(3):
        Ay = (ty[i] - tau[i] * k) / L
        out[i] = -dL / L * Ay + (dty[i] - t[i] * k - tau[i] * dk) / L


# ---------------------------------------------------------------------------- the kinematics
#: column types: how a column moves the frame (for the derivative rules)
SCREW, TRANSLATION, ROOT_ROTATION, PRISMATIC = 0, 1, 2, 3


@njit(cache=True)
def _virtual_columns(table, k):
    """The number of virtual columns of chain k: its coordinate columns, each FFR tip's nf
    replaced by its six screws."""
    nv = table.column_start[k + 1] - table.column_start[k]
    for li in range(table.start[k], table.start[k + 1]):
        if table.links[li, KIND] == LinkKind.FFR_TIP:
            nv += FFR_TIP_VIRTUAL - int(table.params[table.links[li, PARAM], 2])
    return nv


@njit(cache=True)
def _virtual_entries(table, k, nv):
    """The map from chain k's virtual columns to its real ones, by rows: virtual column v is
    sum_e weight[e] (real column index[e]) over e in start[v]:start[v + 1] (one entry of weight 1
    for an ordinary column; the FFR tip rows M for its six screws)."""
    count = 0
    for li in range(table.start[k], table.start[k + 1]):
        kind = table.links[li, KIND]
        if kind == LinkKind.FFR_TIP:
            count += FFR_TIP_VIRTUAL * int(table.params[table.links[li, PARAM], 2])
        elif kind == LinkKind.REVOLUTE:
            count += 1
        elif kind != LinkKind.CONSTANT:
            count += 7
    start = np.empty(nv + 1, dtype=np.int64)
    index = np.empty(count, dtype=np.int64)
    weight = np.empty(count)
    v = 0
    e = 0
    real = 0
    start[0] = 0
    for li in range(table.start[k], table.start[k + 1]):
        kind = table.links[li, KIND]
        if kind == LinkKind.CONSTANT:
            continue
        if kind == LinkKind.FFR_TIP:
            par = table.params[table.links[li, PARAM]]
            off, nf = int(par[1]), int(par[2])
            for a in range(FFR_TIP_VIRTUAL):
                for j in range(nf):
                    index[e] = real + j
                    weight[e] = table.maps[off + a * nf + j]
                    e += 1
                v += 1
                start[v] = e
            real += nf
        else:
            n = 1 if kind == LinkKind.REVOLUTE else 7
            for j in range(n):
                index[e] = real + j
                weight[e] = 1.0
                e += 1
                v += 1
                start[v] = e
            real += n
    return start, index, weight


@njit(cache=True)
def chain_kinematics(table, k, x, F, order, r, R, Jr, Jw, Hr, Hw):
    """The pose of chain k at the coordinates x (charts F for ANCF tips): its origin r (3, m)
    and axes R (3 x 3, columns global), and, for each of its nc coordinate columns (the chain's
    order: :attr:`ChainTable.columns`), Jr[:, i] (m or m/rad per unit coordinate) and
    Jw[:, i] (rad per unit coordinate, global axes). With ``order`` 2 also Hr[:, i, l] =
    dJr[:, i]/dc_l and Hw[:, i, l] = dJw[:, i]/dc_l (module docstring). Jr, Jw (3, nc) and
    Hr, Hw (3, nc, nc) are overwritten."""
    nc = table.column_start[k + 1] - table.column_start[k]
    nv = _virtual_columns(table, k)
    has_tip = False
    for li in range(table.start[k], table.start[k + 1]):
        if table.links[li, KIND] == LinkKind.FFR_TIP:
            has_tip = True
    if not has_tip:
        _screw_kinematics(table, k, x, F, order, r, R, Jr, Jw, Hr, Hw)
        return
    vJr, vJw = np.empty((3, nv)), np.empty((3, nv))
    no = 0 if order < 2 else nv
    vHr, vHw = np.empty((3, no, no)), np.empty((3, no, no))
    _screw_kinematics(table, k, x, F, order, r, R, vJr, vJw, vHr, vHw)
    start, index, weight = _virtual_entries(table, k, nv)
    for a in range(3):
        for j in range(nc):
            Jr[a, j] = 0.0
            Jw[a, j] = 0.0
    for v in range(nv):
        for e in range(start[v], start[v + 1]):
            j, wt = index[e], weight[e]
            for a in range(3):
                Jr[a, j] += wt * vJr[a, v]
                Jw[a, j] += wt * vJw[a, v]
    if order < 2:
        return
    # T[:, v, l] = sum_w H[:, v, w] M[w, l], then H[:, i, l] = sum_v M[v, i] T[:, v, l]
    Tr, Tw = np.zeros((3, nv, nc)), np.zeros((3, nv, nc))
    for v in range(nv):
        for w in range(nv):
            for e in range(start[w], start[w + 1]):
                l, wt = index[e], weight[e]
                for a in range(3):
                    Tr[a, v, l] += vHr[a, v, w] * wt
                    Tw[a, v, l] += vHw[a, v, w] * wt
    for a in range(3):
        for i in range(nc):
            for l in range(nc):
                Hr[a, i, l] = 0.0
                Hw[a, i, l] = 0.0
    for v in range(nv):
        for e in range(start[v], start[v + 1]):
            i, wt = index[e], weight[e]
            for a in range(3):
                for l in range(nc):
                    Hr[a, i, l] += wt * Tr[a, v, l]
                    Hw[a, i, l] += wt * Tw[a, v, l]


@njit(cache=True)
def _screw_kinematics(table, k, x, F, order, r, R, Jr, Jw, Hr, Hw):
    """:func:`chain_kinematics` over the virtual columns of chain k (its columns, each FFR tip
    as its six screws: three translations along the current axes, three revolutes about the
    current x, y', z''); Jr, Jw (3, nv), Hr, Hw (3, nv, nv)."""
    l0, l1 = table.start[k], table.start[k + 1]
    nc = Jr.shape[1]
    for i in range(3):
        r[i] = 0.0
        for j in range(3):
            R[i, j] = 1.0 if i == j else 0.0
    kind_of = np.empty(nc, dtype=np.int64)  # SCREW, TRANSLATION or ROOT_ROTATION
    direction = np.zeros(nc, dtype=np.int64)  # a translation column's global axis
    prism = np.empty((nc, 3))  # a prismatic column's axis (global)
    origin = np.empty((nc, 3))  # the point a rotation column turns about
    root_columns = 0  # the first link's own columns (their mutual derivatives are explicit)
    root_kind = -1
    col = 0
    tmp = np.empty((3, 3))
    E = np.empty((3, 4))
    d = np.empty(3)
    tau = np.empty(3)
    slope_length = 1.0
    for li in range(l0, l1):
        kind = table.links[li, KIND]
        c0 = table.links[li, COORD]
        par = table.params[table.links[li, PARAM]]
        if kind == LinkKind.CONSTANT:
            for i in range(3):
                r[i] += R[i, 0] * par[0] + R[i, 1] * par[1] + R[i, 2] * par[2]
            for i in range(3):
                for j in range(3):
                    tmp[i, j] = R[i, 0] * par[3 + j] + R[i, 1] * par[6 + j] + R[i, 2] * par[9 + j]
            for i in range(3):
                for j in range(3):
                    R[i, j] = tmp[i, j]
        elif kind == LinkKind.REVOLUTE:
            axis = par[0:3]
            for i in range(3):
                Jw[i, col] = par[3] * (R[i, 0] * axis[0] + R[i, 1] * axis[1] + R[i, 2] * axis[2])
                origin[col, i] = r[i]
            kind_of[col] = SCREW
            _rotate_about(R, axis, par[3] * x[c0], tmp)
            for i in range(3):
                for j in range(3):
                    R[i, j] = tmp[i, j]
            col += 1
        elif kind == LinkKind.FFR_TIP:
            off, nf = int(par[1]), int(par[2])
            moved = np.zeros(FFR_TIP_VIRTUAL)  # v = M p
            for a in range(FFR_TIP_VIRTUAL):
                for j in range(nf):
                    moved[a] += table.maps[off + a * nf + j] * x[c0 + j]
            for a in range(3):  # translations along the current axes (the beam's body frame)
                for i in range(3):
                    prism[col + a, i] = R[i, a]
                    Jw[i, col + a] = 0.0
                kind_of[col + a] = PRISMATIC
            shift0 = par[0] + moved[0]
            for i in range(3):
                r[i] += R[i, 0] * shift0 + R[i, 1] * moved[1] + R[i, 2] * moved[2]
            col += 3
            unit = np.zeros(3)
            for a in range(3):  # rotations about x, then y', then z''
                unit[:] = 0.0
                unit[a] = 1.0
                for i in range(3):
                    Jw[i, col] = R[i, a]
                    origin[col, i] = r[i]
                kind_of[col] = SCREW
                _rotate_about(R, unit, moved[3 + a], tmp)
                for i in range(3):
                    for j in range(3):
                        R[i, j] = tmp[i, j]
                col += 1
        elif kind == LinkKind.FREE:
            root_kind = kind
            root_columns = 7
            for i in range(3):
                r[i] = x[c0 + i]
            for j in range(3):
                for a in range(3):
                    Jw[a, col + j] = 0.0
                kind_of[col + j] = TRANSLATION
                direction[col + j] = j
            e = x[c0 + 3:c0 + 7]
            euler_rotation(e, R)
            euler_rate_matrix(e, E)
            s = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]
            for a in range(4):
                for i in range(3):
                    Jw[i, col + 3 + a] = 2.0 * E[i, a] / s
                    origin[col + 3 + a, i] = r[i]
                kind_of[col + 3 + a] = ROOT_ROTATION
            col += 7
        else:  # ANCF_TIP
            root_kind = kind
            root_columns = 7
            Fc = F[int(par[0])]
            for i in range(3):
                r[i] = x[c0 + i]
                d[i] = Fc[i, 0]
            for j in range(3):
                for a in range(3):
                    Jw[a, col + j] = 0.0
                kind_of[col + j] = TRANSLATION
                direction[col + j] = j
            slope_length = _ancf_section(Fc, x[c0 + 3:c0 + 6], x[c0 + 6], R)
            for i in range(3):
                tau[i] = R[i, 0]
            y = np.zeros(3)
            out = np.empty(3)
            for b in range(3):
                y[:] = 0.0
                y[b] = 1.0
                _ancf_rate_columns(d, tau, slope_length, y, out)
                for i in range(3):
                    Jw[i, col + 3 + b] = out[i]
                    origin[col + 3 + b, i] = r[i]
                kind_of[col + 3 + b] = ROOT_ROTATION
            for i in range(3):
                Jw[i, col + 6] = tau[i]
                origin[col + 6, i] = r[i]
            kind_of[col + 6] = ROOT_ROTATION
            col += 7
    # translational columns at the final origin
    dr = np.empty(3)
    for i in range(nc):
        if kind_of[i] == TRANSLATION:
            for a in range(3):
                Jr[a, i] = 1.0 if a == direction[i] else 0.0
        elif kind_of[i] == PRISMATIC:
            for a in range(3):
                Jr[a, i] = prism[i, a]
        else:
            for a in range(3):
                dr[a] = r[a] - origin[i, a]
            cross_into(Jw[:, i], dr, Jr[:, i])
    if order < 2:
        return
    v = np.empty(3)
    for i in range(nc):
        for l in range(nc):
            if i < root_columns and l < root_columns:
                continue  # below
            if l <= i:
                cross_into(Jw[:, l], Jw[:, i], Hw[:, i, l])
                cross_into(Jw[:, l], Jr[:, i], Hr[:, i, l])
            else:
                for a in range(3):
                    Hw[a, i, l] = 0.0
                cross_into(Jw[:, i], Jr[:, l], Hr[:, i, l])
    if root_columns == 0:
        return
    # the first link's own columns among each other
    for i in range(root_columns):
        for l in range(root_columns):
            for a in range(3):
                Hw[a, i, l] = 0.0
                Hr[a, i, l] = 0.0
    c0 = table.links[l0, COORD]
    if root_kind == LinkKind.FREE:
        e = x[c0 + 3:c0 + 7]
        s = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]
        El = np.empty((3, 4))
        unit = np.zeros(4)
        for l in range(4):
            unit[:] = 0.0
            unit[l] = 1.0
            euler_rate_matrix(unit, El)  # dE/de_l (E is linear in e)
            for i in range(4):
                for a in range(3):
                    Hw[a, 3 + i, 3 + l] = 2.0 * El[a, i] / s - 4.0 * e[l] * E[a, i] / (s * s)
        for i in range(4):
            for a in range(3):
                dr[a] = r[a] - x[c0 + a]
            for l in range(4):
                cross_into(Hw[:, 3 + i, 3 + l], dr, v)
                for a in range(3):
                    Hr[a, 3 + i, 3 + l] = v[a]
                cross_into(Jw[:, 3 + i], Jr[:, 3 + l], v)
                for a in range(3):
                    Hr[a, 3 + i, 3 + l] += v[a]
    else:  # ANCF_TIP: rotation columns r0' (3) and theta_1 (1)
        out = np.empty(3)
        y = np.zeros(3)
        for i in range(3):  # d(A e_i)/du_b
            y[:] = 0.0
            y[i] = 1.0
            for b in range(3):
                _ancf_rate_derivative(d, tau, slope_length, y, b, out)
                for a in range(3):
                    Hw[a, 3 + i, 3 + b] = out[a]
        for b in range(3):  # d tau / d u_b
            for a in range(3):
                Hw[a, 6, 3 + b] = ((1.0 if a == b else 0.0) - tau[a] * tau[b]) / slope_length
        for a in range(3):
            dr[a] = r[a] - x[c0 + a]
        for i in range(3, 7):
            for l in range(3, 7):
                cross_into(Hw[:, i, l], dr, v)
                for a in range(3):
                    Hr[a, i, l] = v[a]
                cross_into(Jw[:, i], Jr[:, l], v)
                for a in range(3):
                    Hr[a, i, l] += v[a]


def chain_pose(table: ChainTable, k: int, x, F=None, order: int = 1):
    """(r, R, Jr, Jw, Hr, Hw) of chain k at x (Python front end of :func:`chain_kinematics`;
    Hr, Hw zero unless ``order`` is 2). ``F``: the charts (n, 3, 3) of ANCF tips (default none)."""
    nc = table.width(k)
    r, R = np.empty(3), np.empty((3, 3))
    Jr, Jw = np.zeros((3, nc)), np.zeros((3, nc))
    Hr, Hw = np.zeros((3, nc, nc)), np.zeros((3, nc, nc))
    F = np.zeros((1, 3, 3)) if F is None else np.ascontiguousarray(F, dtype=float)
    chain_kinematics(table, k, np.ascontiguousarray(x, dtype=float), F, order, r, R, Jr, Jw, Hr, Hw)
    return r, R, Jr, Jw, Hr, Hw


# ---------------------------------------------------------------------------- rotations
def rotation_vector_matrix(phi) -> np.ndarray:
    """The rotation matrix of the rotation vector phi (rad): Rodrigues' formula."""
    phi = np.asarray(phi, dtype=float)
    angle = float(np.linalg.norm(phi))
    if angle == 0.0:
        return np.eye(3)
    k = phi / angle
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * K @ K


def euler_parameters(R) -> np.ndarray:
    """Unit Euler parameters (e0 >= 0) of the rotation matrix R (Shepperd's method)."""
    R = np.asarray(R, dtype=float)
    tr = np.trace(R)
    cands = [tr, R[0, 0], R[1, 1], R[2, 2]]
    i = int(np.argmax(cands))
    if i == 0:
        e0 = 0.5 * math.sqrt(1.0 + tr)
        e = np.array([e0, (R[2, 1] - R[1, 2]) / (4 * e0), (R[0, 2] - R[2, 0]) / (4 * e0), (R[1, 0] - R[0, 1]) / (4 * e0)])
    else:
        a = i - 1
        b, c = (a + 1) % 3, (a + 2) % 3
        ea = 0.5 * math.sqrt(max(1.0 + 2 * R[a, a] - tr, 0.0))
        e = np.empty(4)
        e[1 + a] = ea
        e[0] = (R[c, b] - R[b, c]) / (4 * ea)
        e[1 + b] = (R[b, a] + R[a, b]) / (4 * ea)
        e[1 + c] = (R[c, a] + R[a, c]) / (4 * ea)
    if e[0] < 0:
        e = -e
    return e / np.linalg.norm(e)


def rotation_vector(R) -> np.ndarray:
    """The rotation vector (rad, |phi| <= pi) of the rotation matrix R."""
    e = euler_parameters(R)
    s = float(np.linalg.norm(e[1:]))
    if s < 1e-300:
        return np.zeros(3)
    angle = 2.0 * math.atan2(s, e[0])
    return angle * e[1:] / s


# ---------------------------------------------------------------------------- for the kinds
@njit(cache=True)
def chain_columns(table, k):
    """The x indices of chain k's coordinate columns."""
    return table.columns[table.column_start[k]:table.column_start[k + 1]]


@njit(cache=True)
def gather(values, columns):
    """values[columns] as a new array (the chain's coordinates, rates or accelerations)."""
    out = np.empty(columns.shape[0])
    for j in range(columns.shape[0]):
        out[j] = values[columns[j]]
    return out


@njit(cache=True)
def frame_motion(Jr, Jw, Hr, Hw, cd, cdd, vel, w, acc, alpha):
    """The frame's origin velocity vel = Jr c' and angular velocity w = Jw c' (global), and its
    accelerations acc = Jr c'' + sum_il Hr[:, i, l] c'_i c'_l and alpha likewise (the velocity
    products of the chain, exact)."""
    nc = Jr.shape[1]
    for a in range(3):
        sv = sw = sa = sal = 0.0
        for i in range(nc):
            sv += Jr[a, i] * cd[i]
            sw += Jw[a, i] * cd[i]
            sa += Jr[a, i] * cdd[i]
            sal += Jw[a, i] * cdd[i]
            if cd[i] != 0.0:
                hr = hw = 0.0
                for l in range(nc):
                    hr += Hr[a, i, l] * cd[l]
                    hw += Hw[a, i, l] * cd[l]
                sa += hr * cd[i]
                sal += hw * cd[i]
        vel[a] = sv
        w[a] = sw
        acc[a] = sa
        alpha[a] = sal


@njit(cache=True)
def chain_origin_and_axes(table, k, x, F, r, R):
    """The pose (r, R) of chain k at x, without Jacobians."""
    nc = table.column_start[k + 1] - table.column_start[k]
    Jr, Jw = np.empty((3, nc)), np.empty((3, nc))
    H = np.empty((3, 0, 0))
    chain_kinematics(table, k, x, F, 1, r, R, Jr, Jw, H, H)


@njit(cache=True)
def displacement_in_reference(ctx, F, x, root_chain, reference_chain, length, tip, out):
    """out = R_ref^T (tip - r_root - length tau_root): a tip's displacement (m) from its
    undeformed place (the root frame's axis carried out to ``length``), along the axes of
    the reference frame (the beam's hub frame: radial, along the hub axis, tangential)."""
    r, R = np.empty(3), np.empty((3, 3))
    chain_origin_and_axes(ctx.chains, root_chain, x, F, r, R)
    d = np.empty(3)
    for i in range(3):
        d[i] = tip[i] - r[i] - length * R[i, 0]
    chain_origin_and_axes(ctx.chains, reference_chain, x, F, r, R)
    for j in range(3):
        out[j] = R[0, j] * d[0] + R[1, j] * d[1] + R[2, j] * d[2]
