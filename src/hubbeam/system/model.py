"""What every hub-beam system shares (paper Sec. 4): the hub, its drive, the interface.

A system has coordinates x = [theta, q] (hub angle, then the beam formulation's
coordinates), constraints Phi(x, t) = 0 (the clamp, and a drive for a prescribed or
fixed hub) with multipliers lambda (Eq. 77), and a *chart* F: extra state that fixes how
rotations are parametrised (the ANCF reference director; unused by FFR). The solvers,
sensors and the simulation use only the methods listed in :class:`HubSystem`; the two
formulations (:mod:`hubbeam.system.ancf_system`, :mod:`hubbeam.system.ffr_system`)
implement them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hubbeam.system.hub import DriveProfile, hub_frame

#: the hub's axis j0 (global); the hub turns about -j0 for increasing theta (Eq. 74)
AXIS = np.array([0.0, 1.0, 0.0])


@dataclass
class HubSystem:
    """A beam clamped to a hub of radius R (m) with the section twisted by beta (rad).

    Formulation-specific methods: initial_state, constraints (Phi, its Jacobian on the
    leading block of x that the clamp involves, and lambda -> lambda . d2 Phi on that block), static_equations, dynamic_residual, dynamic_equations, linearised,
    axis_chart, remap, chart_margin, better_chart, steady_rotation_rates, energies,
    angular_momentum, dissipated_power, tip_position, surface_strain, centre_line,
    static_force_scale; properties nx, length_scale, mass_scale, constraint_scale.
    """

    beam: object
    radius: float = 0.0
    twist: float = 0.0
    motion: str = "fixed"  # "free" | "prescribed" | "fixed"
    hub_inertia: float = 1.0  # kg m^2 about j0
    hub_torque: float = 0.0  # N m, external torque on the hub (acts on theta)
    drive: DriveProfile = field(default_factory=lambda: DriveProfile("rest"))
    gravity: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tip_force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    tip_moment: np.ndarray = field(default_factory=lambda: np.zeros(3))
    damping: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        self.gravity = np.asarray(self.gravity, dtype=float)
        self.tip_force = np.asarray(self.tip_force, dtype=float)
        self.tip_moment = np.asarray(self.tip_moment, dtype=float)

    def compiled_model(self):
        """Constants for compiled time integration (:mod:`hubbeam.solvers.compiled_alpha`), or
        None when the formulation integrates step by step in Python."""
        return None

    def n_constraints(self, held: bool) -> int:
        """Six clamp equations, and the drive theta = theta_p(t) when the hub is held."""
        return 7 if held else 6

    def drive_angle(self, t: float, held: bool | None = None) -> float | None:
        """theta_p(t) of the driving constraint, or None for a free hub."""
        if held is None:
            held = self.motion != "free"
        if not held:
            return None
        if self.motion == "prescribed":
            return self.drive(t)[0]
        return 0.0

    @property
    def length_scale(self) -> float:
        """Length for relative tolerances on coordinates (m)."""
        return float(self.beam.length)

    @property
    def mass_scale(self) -> float:
        """rho A l: the mass of one element, scales the constraint rows of the dynamics (kg)."""
        return self.beam.section.mass_per_length * self.beam.element_length

    @property
    def constraint_scale(self) -> float:
        """EA / l: scales the constraint rows of the statics to the stiffness entries (N/m)."""
        return self.beam.section.stiffness[0] / self.beam.element_length

    @staticmethod
    def drive_torque(lam: np.ndarray) -> float:
        """Torque the drive applies to the hub (N m): minus the driving constraint's multiplier;
        zero for a free hub (no driving constraint)."""
        return float(-lam[6]) if lam.shape[0] > 6 else 0.0

    def tip_displacement(self, x: np.ndarray) -> dict[str, float]:
        """Tip centroid displacement from its undeformed place, in the hub frame (m)."""
        A = hub_frame(x[0])
        disp = self.tip_position(x) - (self.radius + self.beam.length) * A[:, 0]
        return {"radial": float(disp @ A[:, 0]), "vertical": float(disp @ A[:, 1]), "tangential": float(disp @ A[:, 2])}

    def constraint_violation(self, x: np.ndarray, F: np.ndarray, t: float) -> float:
        """Largest violation of the clamp's position equations (m)."""
        phi, _, _ = self.constraints(x, F, self.drive_angle(t))
        return float(np.max(np.abs(phi[0:3])))
