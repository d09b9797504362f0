"""The figures and numbers of the bundled examples on a moving base: `python docs/figures/base_examples.py`.

Runs `spacecraft3d`, `platform`, `tilted` and `explorer` through the public API (as `hubbeam run`
does; `platform` and `tilted` also without their base's motion or tilt, for comparison), draws
docs/figures/example_{spacecraft3d,platform,tilted,explorer}.png and prints the numbers that
docs/examples.md quotes. Takes about a minute on a 2-core machine once numba's cache is warm.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from hubbeam import api  # noqa: E402
from hubbeam.io.results import to_dataset  # noqa: E402
from hubbeam.io.scenario import load_example  # noqa: E402

OUT = Path(__file__).resolve().parent


def run(name, overrides=()):
    scenario = load_example(name, list(overrides))
    traj, failure = api.run(scenario)
    if failure is not None:
        sys.exit(f"{name}: {failure}")
    label = f"{name} {' '.join(overrides)}".strip()
    print(f"{label}: {traj.steps} steps, {traj.newton_iterations / traj.steps:.2f} Newton iterations per step, "
          f"{traj.wall_time_s:.1f} s of integration")
    return scenario, to_dataset(traj, scenario)


def vector(ds, name):
    return np.column_stack([ds[f"{name}_{c}"].values for c in "xyz"])


def balance(ds):
    """The largest change of total + dissipated - drive (J)."""
    e = ds["energy_total"].values + ds["energy_dissipated"].values - ds["energy_drive"].values
    return float(np.max(np.abs(e - e[0])))


def panels(t, rows, path, title, xlabel="time (s)"):
    fig, axes = plt.subplots(len(rows), 1, figsize=(8, 1.9 * len(rows) + 0.6), sharex=True, squeeze=False)
    for ax, (label, curves) in zip(axes[:, 0], rows):
        for legend, values, style in curves:
            ax.plot(t, values, style, lw=1.3, label=legend)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        if any(legend for legend, _, _ in curves):
            ax.legend(fontsize=8, loc="best")
    axes[-1, 0].set_xlabel(xlabel)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def rms_amplitude(t, y, omega):
    """The amplitude of y's part at frequency omega (rad/s), by least squares with a mean."""
    A = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t)])
    c, *_ = np.linalg.lstsq(A, y, rcond=None)
    return float(np.hypot(c[1], c[2])), float(c[0])


def spacecraft3d():
    sc, ds = run("spacecraft3d")
    t = ds["time"].values
    slew = sc.base.torque.slew
    axis = np.asarray(slew.axis) / np.linalg.norm(slew.axis)
    s = np.where(t < slew.T, slew.angle * (t / slew.T - np.sin(2 * np.pi * t / slew.T) / (2 * np.pi)), slew.angle)
    turned = Rotation.from_rotvec(vector(ds, "attitude")).as_rotvec()  # R(0) = I: the bus axes at t = 0
    along = turned @ axis
    cross = np.linalg.norm(turned - np.outer(along, axis), axis=1)
    rate, torque = vector(ds, "rate"), vector(ds, "torque")
    H = vector(ds, "momentum")
    k = int(np.argmax(cross))
    after = t >= slew.T
    late = t >= 40.0
    print(f"spacecraft3d: the attitude leaves the slew axis by up to {np.degrees(cross[k]):.3f} deg (at {t[k]:.1f} s); "
          f"{np.degrees(along[-1]):.4f} deg about it at {t[-1]:.0f} s ({np.degrees(cross[-1]):.1e} deg off it); "
          f"peak rate about x (not in the slew axis) {np.max(np.abs(rate[:, 0])):.2e} rad/s, about y, z "
          f"{np.max(np.abs(rate[:, 1])):.4f}, {np.max(np.abs(rate[:, 2])):.4f} rad/s; torque peaks "
          f"{', '.join(f'{v:.2f}' for v in np.max(np.abs(torque), axis=0))} N m (x, y, z)")
    print(f"spacecraft3d: panel a's tip swings {1e3 * np.max(np.abs(ds['tip_a_tangential'].values)):.1f} mm during the "
          f"slew; after it ({slew.T:.0f} s) {1e3 * np.max(np.abs(ds['tip_a_tangential'].values[after])):.2f} mm, "
          f"after 40 s {1e6 * np.max(np.abs(ds['tip_a_tangential'].values[late])):.2f} um; panel b's tip within "
          f"{1e6 * np.max(np.abs(ds['tip_a_tangential'].values - ds['tip_b_tangential'].values)):.2f} um of panel a's "
          f"(the slew bends them alike); root strain up to {np.max(np.abs(ds['root_strain_a'].values)):.2e}")
    print(f"spacecraft3d: H about the centre of mass changes by {np.max(np.abs(H - H[0])):.3f} N m s (the law's torque); "
          f"total + dissipated - drive within {balance(ds):.1e} J")
    panels(t, [
        ("about the axis (deg)", [("bus", np.degrees(along), "k-"), ("reference", np.degrees(s), "C3--")]),
        ("off the axis (deg)", [("", np.degrees(cross), "k-")]),
        ("bus rate (rad/s)", [(f"w_{c}", rate[:, i], st) for i, (c, st) in enumerate(zip("xyz", ("C2-", "C0-", "C1--")))]),
        ("PD torque (N m)", [(f"{c}", torque[:, i], st) for i, (c, st) in enumerate(zip("xyz", ("C2-", "C0-", "C1--")))]),
        ("panel tip (mm)", [("panel a, tangential", 1e3 * ds["tip_a_tangential"].values, "C0-"),
                            ("panel b, tangential", 1e3 * ds["tip_b_tangential"].values, "C1--")]),
    ], OUT / "example_spacecraft3d.png", "spacecraft3d: a 30 deg slew about a non-principal axis, two 4 m panels")


def platform():
    sc, ds = run("platform")
    _, still = run("platform", ["base={motion='fixed'}"])
    t = ds["time"].values
    flap, flap_still = ds["tip1_vertical"].values, still["tip1_vertical"].values
    heave, pitch = ds["deck_y"].values, ds["deck_rotation_z"].values
    print(f"platform: heave {heave.min():.2f} to {heave.max():.2f} m, pitch {np.degrees(pitch.min()):.2f} to "
          f"{np.degrees(pitch.max()):.2f} deg; blade 1's tip flap {1e3 * flap.min():.1f} to {1e3 * flap.max():.1f} mm "
          f"(on a still deck {1e3 * flap_still.min():.2f} to {1e3 * flap_still.max():.2f} mm); root strain "
          f"{ds['root_strain'].values.min():.3e} to {ds['root_strain'].values.max():.3e} (still "
          f"{still['root_strain'].values.mean():.3e}); lag {1e6 * np.max(np.abs(ds['tip1_tangential'].values)):.1f} um "
          f"(still {1e6 * np.max(np.abs(still['tip1_tangential'].values)):.2f} um); drive torque within "
          f"{np.max(np.abs(ds['drive_torque'].values)):.3f} N m (still {np.max(np.abs(still['drive_torque'].values)):.3f}); "
          f"total + dissipated - drive within {balance(ds):.1e} J of a drive work up to "
          f"{np.max(np.abs(ds['energy_drive'].values)):.1f} J")
    panels(t, [
        ("deck heave (m)", [("", heave, "k-")]),
        ("deck pitch (deg)", [("", np.degrees(pitch), "k-")]),
        ("blade 1 tip flap (mm)", [("moving deck", 1e3 * flap, "C0-"), ("still deck", 1e3 * flap_still, "C3--")]),
        ("blade 1 tip lag (um)", [("moving deck", 1e6 * ds["tip1_tangential"].values, "C0-"),
                                  ("still deck", 1e6 * still["tip1_tangential"].values, "C3--")]),
    ], OUT / "example_platform.png", "platform: a rotor at 6 rad/s on a heaving and pitching deck")


def tilted():
    sc, ds = run("tilted")
    _, upright = run("tilted", ["hub.orientation=[0.0, 0.0, 0.0]"])
    t = ds["time"].values
    omega = sc.hub.drive.omega_s
    lag, lag_up = ds["lag_strain"].values, upright["lag_strain"].values
    tip, tip_up = ds["tip1_tangential"].values, upright["tip1_tangential"].values
    a_strain, mean_strain = rms_amplitude(t, lag, omega)
    a_up, _ = rms_amplitude(t, lag_up, omega)
    a_tip, _ = rms_amplitude(t, tip, omega)
    a_flap, _ = rms_amplitude(t, ds["tip1_vertical"].values, omega)
    print(f"tilted: blade 1's root edge strain at 1P (omega = {omega:g} rad/s): amplitude {a_strain:.3e} about "
          f"{mean_strain:.3e} (upright: {a_up:.1e}); tip lag at 1P {1e6 * a_tip:.2f} um (upright within "
          f"{1e6 * np.max(np.abs(tip_up)):.2f} um); tip flap at 1P {1e6 * a_flap:.1f} um; drive torque within "
          f"{np.max(np.abs(ds['drive_torque'].values)):.3f} N m (upright {np.max(np.abs(upright['drive_torque'].values)):.3f}: "
          "three blades' 1P gravity torques cancel)")
    azimuth = np.degrees(ds["hub_angle"].values)
    panels(t, [
        ("tip lag (um)", [("tilted 5 deg", 1e6 * tip, "C0-"), ("upright", 1e6 * tip_up, "C3--")]),
        ("root edge strain", [("tilted 5 deg", lag, "C0-"), ("upright", lag_up, "C3--")]),
        ("tip flap (mm)", [("tilted 5 deg", 1e3 * ds["tip1_vertical"].values, "C0-"),
                           ("upright", 1e3 * upright["tip1_vertical"].values, "C3--")]),
        ("hub angle (turns)", [("", azimuth / 360.0, "k-")]),
    ], OUT / "example_tilted.png", "tilted: blade 1 of a rotor at 6 rad/s on a shaft tilted 5 deg under gravity")


def explorer():
    sc, ds = run("explorer")
    t = ds["time"].values
    R = Rotation.from_rotvec(vector(ds, "attitude")).as_matrix()
    H = vector(ds, "momentum")
    h = H / np.linalg.norm(H, axis=1)[:, None]
    angle = {axis: np.degrees(np.arccos(np.clip(np.einsum("ni,ni->n", R[:, :, i], h), -1.0, 1.0)))
             for i, axis in enumerate("xyz")}
    nutation = angle["y"]
    # the major axis (z) ends along -H or +H: its angle from the line of H
    major = np.minimum(angle["z"], 180.0 - angle["z"])
    system = api.build_system(sc)
    x, F = system.initial_state()
    inertia = []
    for e in np.eye(3):  # the rigid craft's inertia about its centre of mass, straight antennas
        v, _ = system.rigid_rates(x, F, angular_velocity=e)
        m = system.momenta(x, v, F)
        inertia.append(float(e @ (m["angular"] - np.cross(m["centre_of_mass"], m["linear"]))))
    h0 = float(np.linalg.norm(H[0]))
    kinetic = ds["energy_kinetic"].values
    crossing = {a: float(t[np.argmax(nutation >= a)]) for a in (10.0, 45.0, 80.0)}
    print(f"explorer: rigid inertia {', '.join(f'{j:.4f}' for j in inertia)} kg m^2 (x, y, z); H = {h0:.4f} N m s, "
          f"kept to {np.max(np.abs(H - H[0])):.1e}; nutation {nutation[0]:.2f} deg at 0, passes "
          + ", ".join(f"{a:.0f} deg at {s:.0f} s" for a, s in crossing.items())
          + f"; at {t[-1]:.0f} s the major axis z is {major[-1]:.1f} deg from the line of H; kinetic energy "
          f"{kinetic[0]:.4f} J -> {kinetic[-1]:.4f} J (a spin about z: H^2/(2 I_z) = {h0**2 / (2 * inertia[2]):.4f} J), "
          f"dissipated {ds['energy_dissipated'].values[-1]:.4f} J, total + dissipated within {balance(ds):.1e} J; "
          f"spin rate about z at the end {np.abs(vector(ds, 'rate')[-1, 2]):.3f} rad/s (H / I_z = "
          f"{h0 / inertia[2]:.3f}); antenna tip along the spin axis up to "
          f"{1e3 * np.max(np.abs(ds['tip_a_vertical'].values)):.0f} mm")
    panels(t, [
        ("angle to H (deg)", [("y (minor axis: the spin)", nutation, "C0-"), ("z (major axis)", angle["z"], "C3-")]),
        ("body rate (rad/s)", [(f"w_{c}", vector(ds, "rate")[:, i], st)
                               for i, (c, st) in enumerate(zip("xyz", ("C2-", "C0-", "C3-")))]),
        ("energy (J)", [("kinetic", kinetic, "k-"), ("dissipated", ds["energy_dissipated"].values, "C1--"),
                        ("H^2 / (2 I_z)", np.full_like(t, h0**2 / (2 * inertia[2])), "C3:")]),
        ("antenna tip (mm)", [("along the spin axis", 1e3 * ds["tip_a_vertical"].values, "C0-")]),
    ], OUT / "example_explorer.png", "explorer: from a spin about the minor axis to a flat spin")


def main():
    for name, draw in (("spacecraft3d", spacecraft3d), ("platform", platform), ("tilted", tilted),
                       ("explorer", explorer)):
        if len(sys.argv) < 2 or name in sys.argv[1:]:
            draw()


if __name__ == "__main__":
    main()
