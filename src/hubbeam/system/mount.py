"""Where a beam sits on its frame: azimuth, radius, twist and precone (the root placement).

Beam k with azimuth psi, radius R, twist beta and precone p hangs on the hub frame
A_h(theta) (Eq. 74; on a moving base, the hub's current frame): its own hub frame is
A_h(theta + psi) = A_h(theta) A_h(psi) (axes i_k, j_h, k_k); its root is at R i_k; its
undeformed axis is i_k tilted out of the hub plane by p towards +j_h (a rotation by p about
k_k): the axis frame a = A_h(theta + psi) R_k(p) (a_1 the axis, a_2, a_3 = k_k); its section
is turned about that axis by -beta exactly as a single beam's is (docs/scenario.md, Eq. 79),
so the clamped root section frame [tau m n] is

    tau = a_1,   m = cos(beta) a_2 - sin(beta) a_3,   n = sin(beta) a_2 + cos(beta) a_3.

With beta = 0 the width (m) lies in the plane of the axis and j_h. A beam at azimuth 180 deg
with twist -beta is the mirror image (in the plane through j_h and k_h(theta)) of one at 0 deg
with +beta. In the system's frames (:mod:`hubbeam.system.frames`) the mount is two constant
links after the hub's: :meth:`Mount.axis_link` to the axis frame (where joint angles turn,
the joint frame of docs/joints.md), then :meth:`Mount.twist_link` to the section.

A beam on another beam's tip (``parent``, its index among the system's beams) hangs on the
parent's tip frame (:meth:`hubbeam.system.parts.BeamPart.tip_frame`: the parent's tip section
turned back by its twist and tip pretwist, so that, undeformed, it is the parent's axis frame
carried to the tip); azimuth and radius do not apply there, precone and twist act as on the
hub. A ``joint`` (:class:`hubbeam.system.joints.Joint`) puts its revolute axes between the
axis frame and the twist (:meth:`Mount.joint_links`); without one the root is clamped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from hubbeam.system.chains import Chain, ChainTable, Link, constant, revolute
from hubbeam.system.frames import chain_pose

if TYPE_CHECKING:
    from hubbeam.system.joints import Joint


def hub_rotation(angle: float) -> np.ndarray:
    """A_h(angle) of Eq. 74: the rotation by ``angle`` about -j (columns i_h, j_h, k_h)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def _about_k(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def about_axis(angle: float) -> np.ndarray:
    """The rotation by ``angle`` (rad) about the beam axis (the frame's first axis)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


@dataclass(frozen=True)
class Mount:
    """Root placement of one beam (SI units, angles in rad): on the hub, or on the tip of beam
    ``parent`` (its index), clamped or on a ``joint``."""

    radius: float = 0.0
    twist: float = 0.0
    azimuth: float = 0.0
    precone: float = 0.0
    parent: int | None = None
    joint: Joint | None = None

    def reference_link(self) -> Link:
        """The hub frame to the beam's own hub frame A_h(psi) (axes i_k, j_h, k_k; origin on the
        axis); on a parent's tip frame, nothing (the reference is that frame)."""
        if self.parent is not None:
            return constant()
        return constant(rotation=hub_rotation(self.azimuth))

    def axis_link(self) -> Link:
        """The hub frame to the axis frame: the root at R i_k, axes A_h(psi) R_k(p); on a parent's
        tip frame, the turn by the precone alone."""
        if self.parent is not None:
            return constant(rotation=_about_k(self.precone))
        A = hub_rotation(self.azimuth)
        return constant(A @ np.array([self.radius, 0.0, 0.0]), A @ _about_k(self.precone))

    @property
    def joint_count(self) -> int:
        """Joint angles at the root (0 when clamped)."""
        return 0 if self.joint is None else self.joint.count

    def joint_links(self, first: int) -> tuple[Link, ...]:
        """The joint's revolute links, its angles from x[first] (none when clamped)."""
        return () if self.joint is None else self.joint.links(first)

    def twist_link(self) -> Link:
        """The axis frame to the root section frame: turned by -beta about the axis."""
        return constant(rotation=about_axis(-self.twist))

    # ------------------------------------------------------------ on an upright hub (Python geometry)
    def _upright(self, theta: float, *links: Link) -> tuple[np.ndarray, np.ndarray]:
        chain = Chain((revolute(0, (0.0, 1.0, 0.0), -1.0), *links))
        return chain_pose(ChainTable.of([chain]), 0, np.array([float(theta)]))[:2]

    def frame(self, theta: float) -> np.ndarray:
        """Clamped root section frame [tau m n] (columns, global) at hub angle theta of an upright hub."""
        return self._upright(theta, self.axis_link(), self.twist_link())[1]

    def hub_frame(self, theta: float) -> np.ndarray:
        """The beam's own hub frame [i_k j0 k_k] (columns) at hub angle theta of an upright hub."""
        return self._upright(theta, self.reference_link())[1]

    def root(self, theta: float) -> np.ndarray:
        """Root position R i_k (m) on an upright hub at the origin."""
        return self._upright(theta, self.axis_link())[0]
