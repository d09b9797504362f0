"""The frames of a system as chains (:mod:`hubbeam.system.chains`, evaluated by
:mod:`hubbeam.system.frames`): the base's, the shaft's, the hub's, and each beam's reference,
joint and root section frames, to which the rigid bodies add theirs."""

from __future__ import annotations

import numpy as np

from hubbeam.system.base import Base, HubPlacement
from hubbeam.system.chains import Chain, ChainTable, revolute
from hubbeam.system.frames import chain_pose
from hubbeam.system.layout import Layout

#: the hub's axis in its own frame: theta turns the hub about -j (Eq. 74)
HUB_AXIS = np.array([0.0, 1.0, 0.0])


class Frames:
    """The frames of a system as chains (:mod:`hubbeam.system.frames`): the base's, the shaft's
    (the hub frame at theta = 0, the axes ANCF charts are chosen in), the hub's, and for every
    beam its reference frame (its own hub frame A_h(theta + psi): the tip deflection's axes; on
    a parent beam, the parent's tip frame), its joint frame (its axis frame, where its joint
    turns) and its root section frame; rigid bodies add theirs with :meth:`add`. A beam on a
    parent hangs on the parent's tip frame (:meth:`BeamPart.tip_frame`), so the parent comes
    first."""

    def __init__(self, base: Base, placement: HubPlacement, beams, layout: Layout) -> None:
        self._chains: list[Chain] = []
        self._merged: list[Chain] = []  # each chain's :meth:`Chain.merged`, to find an equal one
        base_chain = base.chain(layout.base_x.start)
        self.base = self.add(base_chain)
        self.shaft = self.add(base_chain.then(placement.link()))
        hub = self.chain(self.shaft).then(revolute(layout.theta, HUB_AXIS, -1.0))
        self.hub = self.add(hub)
        self._reference, self._root, self._joint, tips = [], [], [], []
        for k, part in enumerate(beams):
            mount = part.mount
            if mount.parent is None:
                frame, reference = hub, hub.then(mount.reference_link())
            elif 0 <= mount.parent < k:
                frame = reference = tips[mount.parent]
            else:
                raise ValueError(f"beam {k} hangs on beam {mount.parent}: a parent must come before its child")
            axis = frame.then(mount.axis_link())
            root = axis.then(*mount.joint_links(layout.joint_x(k).start), mount.twist_link())
            self._reference.append(self.add(reference))
            self._joint.append(self.add(axis))
            self._root.append(self.add(root))
            tips.append(part.tip_frame(layout.beam_x(k).start, k, root))
        # chains whose Hessians (second) or velocity products only (products) the equations read:
        # the roots of beams clamped by constraints (the ANCF clamps' second derivatives) and of
        # the others (the FFR beams' accelerations), and what :meth:`needs_hessian` and
        # :meth:`needs_products` add
        self._second: set[int] = {self._root[k] for k in range(len(self._root)) if layout.clamped[k]}
        self._products: set[int] = {self._root[k] for k in range(len(self._root)) if not layout.clamped[k]}
        self._table: ChainTable | None = None

    def add(self, chain: Chain) -> int:
        """Register a chain; returns its index. A chain equal to one registered before, link by
        link once constants are merged (:meth:`Chain.merged`: a hub on the base's origin and axes,
        a beam's reference at azimuth 0, a root without twist, a free base's centre of mass at its
        origin), gets that chain's index, so that the frame is evaluated once per evaluation of the
        system's equations (:func:`~hubbeam.system.frames.evaluate_chains`), not once per name."""
        key = chain.merged()
        for index, known in enumerate(self._merged):
            if known == key:
                return index
        self._chains.append(chain)
        self._merged.append(key)
        self._table = None
        return len(self._chains) - 1

    def chain(self, index: int) -> Chain:
        return self._chains[index]

    def root(self, k: int) -> int:
        """Beam k's root section frame."""
        return self._root[k]

    def reference(self, k: int) -> int:
        """Beam k's reference frame (its own hub frame: radial, along the hub axis, tangential;
        on a parent, the parent's tip frame)."""
        return self._reference[k]

    def joint(self, k: int) -> int:
        """Beam k's joint frame (a, b, c): its axis frame before its joint and twist."""
        return self._joint[k]

    def needs_hessian(self, index: int) -> int:
        """Mark chain ``index`` as one whose derivatives Hr, Hw the system's equations read
        (:func:`hubbeam.system.frames.evaluate_motion` evaluates only those, and the velocity
        products of those marked by :meth:`needs_products`); returns the index."""
        self._second.add(index)
        self._table = None
        return index

    def needs_products(self, index: int) -> int:
        """Mark chain ``index`` as one whose velocity products h_r, h_w (its acceleration: a rigid
        body's frame) the system's equations read, and its derivatives only for statics and
        modes (:func:`hubbeam.system.frames.evaluate_motion`); returns the index."""
        self._products.add(index)
        self._table = None
        return index

    @property
    def table(self) -> ChainTable:
        """Every chain in arrays; the Hessians of the roots of beams clamped by constraints (the
        ANCF clamps' second derivatives) and of the chains marked by :meth:`needs_hessian`, and
        the velocity products of the other roots (the FFR beams') and of the chains marked by
        :meth:`needs_products` (the rigid bodies'), are evaluated in the equations."""
        if self._table is None:
            self._table = ChainTable.of(self._chains, self._second | self._products, self._second)
        return self._table

    def pose(self, index: int, x, F=None) -> tuple[np.ndarray, np.ndarray]:
        """(origin, axes) of chain ``index`` at x."""
        r, R, *_ = chain_pose(self.table, index, x, F)
        return r, R

    def motion(self, index: int, x, v, F=None):
        """(origin, axes, origin velocity, angular velocity) of chain ``index`` at (x, v) (global)."""
        r, R, Jr, Jw, _, _ = chain_pose(self.table, index, x, F)
        cols = self.chain(index).coordinates
        cd = np.asarray(v)[cols] if cols else np.zeros(0)
        return r, R, Jr @ cd, Jw @ cd
