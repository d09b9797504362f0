"""Laws on the system's coordinates: the hub's drive constraint or torque law.

The hub angle theta is a coordinate of the system (:class:`~hubbeam.system.layout.Layout`);
its hub is driven one of two ways (:class:`~hubbeam.system.hub.Hub`):

- held (prescribed or fixed): the driving constraint theta - theta_p(t) = 0 (paper Eq. 82)
  with its multiplier lambda_drive, the torque the drive applies being -lambda_drive;
- free: the applied torque T(t, theta, theta') of its torque law
  (:mod:`hubbeam.system.laws`), about -j_h in the sense of theta.

The torque acts between the base and the hub, so its generalized force is on theta alone:
the base's share of the reaction follows from theta being relative to the base. Both add to
the drive power (T - lambda_drive) theta' of the energy balance. The kind "hub laws"
(:data:`KIND`) holds them for the compiled equations.
"""

from __future__ import annotations

from typing import NamedTuple

from numba import njit

from hubbeam.system import terms
from hubbeam.system.assembly import add_entry
from hubbeam.system.law_kernels import DriveKind, drive_values, torque_values
from hubbeam.system.laws import DriveProfile, TorqueLaw


class HubLaws(NamedTuple):
    """The hub's law: ``held`` with the ``drive`` (CompiledDrive) and its multiplier's place in
    lambda, or free with the ``torque`` (CompiledTorque)."""

    held: bool
    drive_lambda: int  # the drive multiplier's place in lambda (-1 for a free hub)
    drive: tuple
    torque: tuple


def pack_hub_laws(system, layout) -> HubLaws:
    hub = system.hub
    held = layout.held
    # a fixed hub is held at theta = 0: the profile 'rest'; a held hub applies no torque law
    drive = hub.drive if hub.motion == "prescribed" else DriveProfile("rest")
    torque = hub.torque if (not held and hub.torque.compilable) else TorqueLaw()
    return HubLaws(held, -1 if layout.drive_lambda is None else layout.drive_lambda, tuple(drive.compiled()),
                   tuple(torque.compiled()))


@njit(cache=True, inline="always")
def drive_angle(drive, t):
    """theta_p(t) of the driving constraint (a fixed hub has the profile 'rest')."""
    return drive_values(drive[0], drive[1], drive[2], drive[3], t)[0]


@njit(cache=True, inline="always")
def applied_torque(torque, t, theta, omega):
    """(T, dT/dtheta, dT/domega) of the hub's torque law (N m)."""
    tq = torque
    return torque_values(tq[0], tq[1], tq[2], tq[3], tq[4], tq[5], tq[6], tq[7], t, theta, omega)


def hub_law_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor,
                      exact_stiffness, want_matrix, res, ab, brow, bcol, bb):
    """-coef_k load_factor T on theta's row; a held hub's drive constraint, scale (theta -
    theta_p(t)), in its multiplier's row and coef_k lambda_drive on theta's."""
    zx, zl, ku = ctx.z_of_x, ctx.z_of_lambda, ctx.ku
    z_theta = zx[ctx.theta]
    theta, omega = x[ctx.theta], v[ctx.theta]
    torque, d_theta, d_omega = applied_torque(pack.torque, t, theta, omega)
    row = -load_factor * torque
    z_drive = zl[pack.drive_lambda] if pack.held else -1
    if pack.held:
        row += lam[pack.drive_lambda]
        res[z_drive] = scale * (theta - drive_angle(pack.drive, t))
    res[z_theta] += coef_k * row
    if want_matrix:
        add_entry(ab, brow, bcol, bb, ku, z_theta, z_theta, -load_factor * (coef_k * d_theta + coef_c * d_omega))
        if pack.held:
            add_entry(ab, brow, bcol, bb, ku, z_theta, z_drive, scale)
            add_entry(ab, brow, bcol, bb, ku, z_drive, z_theta, scale)
    return 2.0, 0.0


def hub_law_drive_power(pack, ctx, F, t, x, v, lam):
    """(T - lambda_drive) theta' (W): the applied torque's and the drive's power."""
    torque = applied_torque(pack.torque, t, x[ctx.theta], v[ctx.theta])[0]
    if pack.held:
        torque -= lam[pack.drive_lambda]
    return torque * v[ctx.theta]


def hub_law_powers_possible(pack: HubLaws, ctx) -> bool:
    """Whether the hub's law can have a power that is not zero (:func:`hubbeam.system.terms.with_powers`):
    not for a fixed hub (held at rest, no torque law): its drive's reaction does no work."""
    return not (pack.held and int(pack.drive[0]) == DriveKind.REST)


KIND = terms.register(HubLaws, pack_hub_laws, hub_law_equations, drive_power=hub_law_drive_power,
                      powers_possible=hub_law_powers_possible,
                      counts_references=False)
