"""Helpers for the multi-beam system tests: independent rigid-body oracles and record arrays.

Nothing here uses the code's mass matrices or frames: the rigid inertia about the hub axis
is integrated from the mount data (radius R, twist beta, azimuth psi, precone p), the
sections and the tip bodies, with the root frame written out from the convention of
:mod:`hubbeam.system.mount` in the beam's own hub frame (i_k, j0, k_k):

    tau = (cos p, sin p, 0),  a2 = (-sin p, cos p, 0),  a3 = (0, 0, 1),
    m = cos(beta) a2 - sin(beta) a3,  n = sin(beta) a2 + cos(beta) a3.
"""

from __future__ import annotations

import numpy as np

from hubbeam.system.multibody import MultibodySystem

#: the parts of a tip_deflection record, in this order in the arrays below
TIP_PARTS = ("radial", "vertical", "tangential")
J0 = np.array([0.0, 1.0, 0.0])


def root_frame(beta: float, precone: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(tau, m, n) of an undeformed beam in its own hub frame (i_k, j0, k_k)."""
    cp, sp = np.cos(precone), np.sin(precone)
    tau = np.array([cp, sp, 0.0])
    a2 = np.array([-sp, cp, 0.0])
    a3 = np.array([0.0, 0.0, 1.0])
    m = np.cos(beta) * a2 - np.sin(beta) * a3
    n = np.sin(beta) * a2 + np.cos(beta) * a3
    return tau, m, n


def rigid_axis_inertia(system: MultibodySystem, gauss: int = 6) -> float:
    """Moment of inertia (kg m^2) about the hub axis of the hub, the straight beams and their
    tip bodies turning rigidly together: rho A int (R + s cos p)^2 ds by Gauss quadrature, the
    sections' rotary inertia rho (I_tau (j.tau)^2 + I_m (j.m)^2 + I_n (j.n)^2) L, and each tip
    body's m d_cm^2 (d_cm its centre's distance from the axis) plus its principal inertias
    projected on j0."""
    x, w = np.polynomial.legendre.leggauss(gauss)
    total = float(system.hub.inertia)
    for part in system.beams:
        R, beta, _, p = (part.mount.radius, part.mount.twist, part.mount.azimuth, part.mount.precone)
        sec = part.section
        length = part.length
        s = 0.5 * length * (x + 1.0)
        total += sec.mass_per_length * np.sum(0.5 * length * w * (R + s * np.cos(p)) ** 2)
        tau, m, n = root_frame(beta, p)
        total += sec.density * length * ((sec.i_y + sec.i_z) * (J0 @ tau) ** 2 + sec.i_y * (J0 @ m) ** 2
                                         + sec.i_z * (J0 @ n) ** 2)
        body = part.tip_body
        if body is not None:
            c = np.asarray(body.offset)
            r_cm = np.array([R, 0.0, 0.0]) + (length + c[0]) * tau + c[1] * m + c[2] * n
            total += body.mass * (r_cm @ r_cm - (r_cm @ J0) ** 2)
            total += sum(Jk * (J0 @ e) ** 2 for Jk, e in zip(body.inertia, (tau, m, n)))
    return total


def tips(records) -> np.ndarray:
    """tip_deflection records as an array (time, [radial, vertical, tangential])."""
    return np.array([[r[k] for k in TIP_PARTS] for r in records])


def parts_of(records, key: str) -> np.ndarray:
    """One part of dict records (energy) as an array over time."""
    return np.array([float(r[key]) for r in records])
