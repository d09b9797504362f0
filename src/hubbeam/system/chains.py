"""Chains: a frame of a system described as a product of links (:class:`Link`, :class:`Chain`:
what the parts declare), and every chain of a system packed into arrays for compiled code with
the place where their kinematics are kept (:class:`ChainTable`). The kinematics themselves,
and what each link kind means, are :mod:`hubbeam.system.frames`'."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

#: what is evaluated of a chain (:attr:`ChainTable.orders`, :func:`hubbeam.system.frames.chain_kinematics_into`):
#: its pose and Jacobians; and its velocity products h_r = sum_il Hr[:, i, l] c'_i c'_l, h_w
#: likewise; and its derivatives Hr, Hw themselves
POSE, PRODUCTS, HESSIANS = 1, 2, 3
#: columns of a chain's scratch rows (:func:`hubbeam.system.frames.chain_kinematics_into`)
W_WIDTH = 15
#: column types: how a column moves the frame (for the derivative rules); TIP_COMBINATION: a
#: column of an FFR tip (its translations and rotations combined, :mod:`hubbeam.system.frames`)
SCREW, TRANSLATION, ROOT_ROTATION, TIP_COMBINATION = 0, 1, 2, 3
#: the scratch rows' columns (one row per coordinate column of a chain): the column's type, a
#: translation's axis (an FFR tip's column: its link's params row), the point a rotation turns
#: about (3); an FFR tip's column: its index j among the tip's columns, and on the tip's first
#: column the tip's three rotation axes w_x, w_y', w_z'' (9)
W_TYPE, W_DIRECTION, W_ORIGIN, W_INDEX, W_AXES = 0, 1, 2, 5, 6  # W_WIDTH columns in all


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
#: virtual screws of an FFR tip: translations along x, y, z, then rotations about x, y', z''
FFR_TIP_VIRTUAL = 6


@dataclass(frozen=True)
class Link:
    """One elementary transform. ``coordinate``: where its first coordinate sits in x (-1 for a
    constant link); ``offset`` (m) and ``rotation`` (3 x 3) of a constant link; ``axis`` (unit,
    in the current frame) and ``sign`` of a revolute one; ``chart``: the index in F of an ANCF
    tip's rotation chart; ``length`` (m) and ``rows`` (M = [N_L; Phi_L], 6 x nf) of an FFR tip."""

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
    def is_identity(self) -> bool:
        """A constant link that moves nothing: offset zero and rotation exactly the unit matrix."""
        return (self.kind == LinkKind.CONSTANT and all(v == 0.0 for v in self.offset)
                and all(self.rotation[i][j] == (1.0 if i == j else 0.0) for i in range(3) for j in range(3)))

    @property
    def coordinates(self) -> int:
        if self.kind == LinkKind.FFR_TIP:
            return len(self.rows[0])
        return LINK_COORDINATES[self.kind]

    def params(self) -> np.ndarray:
        """The link's 13 numbers for compiled code: offset (3) and rotation (9, row-major) of a
        constant link; axis (3) and sign of a revolute one; the chart's index of an ANCF tip;
        an FFR tip's length, its rows' place in :attr:`ChainTable.maps` (set there) and nf."""
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
        elif self.kind == LinkKind.FFR_TIP:
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
    """A frame as a product of links (the first may be FREE or ANCF_TIP; an FFR_TIP never is)."""

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

    def merged(self) -> "Chain":
        """The same frame with every run of constant links merged into one and a merged link that
        is exactly the identity (no offset, the unit rotation) left out: fewer products to
        evaluate, and chains that differ only by such links become equal (:meth:`Frames.add
        <hubbeam.system.system_frames.Frames.add>` then keeps one). The pose and its derivatives
        are the same (a product by the identity changes at most the sign of a zero)."""
        out: list[Link] = []
        for link in self.links:
            if link.kind == LinkKind.CONSTANT and out and out[-1].kind == LinkKind.CONSTANT:
                prev = out.pop()
                R1, t1 = np.array(prev.rotation), np.array(prev.offset)
                R2, t2 = np.array(link.rotation), np.array(link.offset)
                link = constant(t1 + R1 @ t2, R1 @ R2)
            out.append(link)
        kept = tuple(link for link in out if not link.is_identity)
        if kept and kept[0].kind == LinkKind.FFR_TIP:  # an FFR tip is never first: the identity stays before it
            kept = (constant(),) + kept
        return Chain(kept)

    @property
    def coordinates(self) -> list[int]:
        """x indices of the chain's coordinate columns, in chain order."""
        out = []
        for link in self.links:
            out += [link.coordinate + j for j in range(link.coordinates)]
        return out


def _prefix(merged, k: int) -> int:
    """The earlier chain of ``merged`` (each a tuple of merged links) with the most links whose
    links begin chain k's (-1: none; nor where either holds an ANCF or FFR tip)."""
    tips = (LinkKind.ANCF_TIP, LinkKind.FFR_TIP)
    if any(link.kind in tips for link in merged[k]):
        return -1
    best, size = -1, 0
    for j in range(k):
        n = len(merged[j])
        if size < n <= len(merged[k]) and merged[k][:n] == merged[j]:
            best, size = j, n
    return best


class ChainTable(NamedTuple):
    """Every chain of a system in arrays for compiled code (:meth:`of`), and the place where
    their kinematics at the current state are kept (:func:`evaluate_chains`: once per evaluation
    of the system's equations, read by every part that hangs on a frame)."""

    links: np.ndarray  # int64 (n_links, 3): kind, first coordinate's x index, row in params
    params: np.ndarray  # (n_links, 13): Link.params
    start: np.ndarray  # int64 (n_chains + 1): chain k's links are links[start[k]:start[k + 1]]
    columns: np.ndarray  # int64 (n_columns,): the chains' coordinate columns' x indices
    column_start: np.ndarray  # int64 (n_chains + 1): chain k's columns are columns[column_start[k]:...]
    pose: np.ndarray  # (n_chains, 3, 4): each chain's origin (column 0) and axes (1:4) at the state
    jac: np.ndarray  # (n_chains, 2, 3, w): Jr, Jw of each chain's columns (w: the widest chain's)
    hess: np.ndarray  # (n_chains, 2, 3, w, w): Hr, Hw
    products: np.ndarray  # (n_chains, 2, 3): the velocity products h_r, h_w (:func:`evaluate_motion`)
    work: np.ndarray  # (w, W_WIDTH): scratch of :func:`chain_kinematics_into` for the widest chain
    maps: np.ndarray  # (n,): the FFR tips' rows M (6 x nf, row-major), each from its link's params[1]
    # int64 (n_chains,): what the system's equations read of each chain beyond its pose and
    # Jacobians (:func:`evaluate_motion`): nothing (POSE), its velocity products (PRODUCTS) or
    # its derivatives hess too (HESSIANS)
    orders: np.ndarray
    # int64 (n_chains,): an earlier chain whose links (merged) begin this chain's, the longest,
    # or -1; neither of them holds an ANCF or FFR tip. Where the earlier chain is evaluated in
    # the same call, this one continues from its pose and Jacobians (:func:`evaluate_motion`,
    # to its velocity products at most): a free base's frames share the base's pose
    prefix: np.ndarray
    # the link kinds beyond constants and revolutes that some chain holds: True, or None when none
    # does, so that numba compiles the kinematics without that kind's code (:func:`evaluate_chains`)
    free_links: bool | None
    ancf_tips: bool | None
    ffr_tips: bool | None

    @classmethod
    def of(cls, chains, second=None, hessians=None) -> "ChainTable":
        """The table of ``chains``; ``second``: the indices of the chains whose second-order
        terms the system's equations read (default every chain's), their velocity products
        only unless among ``hessians`` (default all of ``second``), whose derivatives hess
        they read too (:func:`hubbeam.system.frames.evaluate_motion`)."""
        links, params, start, columns, cstart, maps = [], [], [0], [], [0], []
        merged = [chain.merged().links for chain in chains]
        for chain in chains:
            for link in chain.merged().links:
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
        n = len(start) - 1
        held = {row[KIND] for row in links}
        present = lambda kind: True if int(kind) in held else None  # noqa: E731
        w = max((cstart[k + 1] - cstart[k] for k in range(n)), default=0)
        return cls(ints(links, (len(links), 3)), np.array(params, dtype=float).reshape(len(params), 13),
                   ints(start, (len(start),)), ints(columns, (len(columns),)), ints(cstart, (len(cstart),)),
                   np.zeros((n, 3, 4)), np.zeros((n, 2, 3, w)), np.zeros((n, 2, 3, w, w)), np.zeros((n, 2, 3)),
                   np.zeros((w, W_WIDTH)), np.array(maps, dtype=float),
                   np.array([(POSE if second is not None and k not in second else
                              HESSIANS if hessians is None or k in hessians else PRODUCTS) for k in range(n)],
                            dtype=np.int64), ints([_prefix(merged, k) for k in range(n)], (n,)),
                   present(LinkKind.FREE), present(LinkKind.ANCF_TIP), present(LinkKind.FFR_TIP))

    def width(self, k: int) -> int:
        """Number of coordinate columns of chain k."""
        return int(self.column_start[k + 1] - self.column_start[k])
