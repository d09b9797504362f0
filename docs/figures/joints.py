"""The figures of the joints page and the joint examples: `python docs/figures/joints.py`.

Draws docs/figures/joint_frame.png (the joint frame and the named axes), runs the bundled
`articulated`, `deploy` and `arm2` through the public API (as `hubbeam run` does) and draws
docs/figures/example_{articulated,deploy,arm2}.png, and computes the articulated rotor's
Campbell diagram (docs/figures/campbell_articulated.png). Prints the numbers the pages quote.
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from hubbeam import api  # noqa: E402
from hubbeam.io.results import to_dataset  # noqa: E402
from hubbeam.io.scenario import load_example  # noqa: E402

OUT = Path(__file__).resolve().parent
sys.path.insert(0, str(OUT))
from examples import panels  # noqa: E402  (the examples' figure layout: one panel per quantity)


def run(name, state=False):
    scenario = load_example(name)
    traj, failure = api.run(scenario, state=state)
    if failure is not None:
        sys.exit(f"{name}: {failure}")
    print(f"{name}: {traj.steps} steps, {traj.newton_iterations / traj.steps:.2f} Newton iterations per step, "
          f"{traj.wall_time_s:.2f} s of integration")
    return scenario, traj, to_dataset(traj, scenario)


def joint_frame():
    """The joint frame (a, b, c) at a beam's root on the hub, and the named axes' positive senses."""
    fig = plt.figure(figsize=(7.5, 6.0))
    ax = fig.add_subplot(projection="3d")
    view = lambda p: np.array([p[0], -p[2], p[1]])  # noqa: E731  (global x, y, z) -> plot (x, -z, y): j0 up
    R = 0.5
    hub = np.array([[R * np.cos(t), 0.0, R * np.sin(t)] for t in np.linspace(0, 2 * np.pi, 80)])
    ax.plot(*view(hub.T), color="0.55")
    ax.plot(*view(np.array([[0, -0.2, 0], [0, 1.1, 0]]).T), color="0.3", ls="--")
    ax.text(*view([0.0, 1.15, 0.0]), "hub axis j0", fontsize=9)
    turn = np.array([[0.25 * np.cos(t), 0.9, 0.25 * np.sin(t)] for t in np.linspace(-0.3, 1.6 * np.pi, 40)])
    ax.plot(*view(turn.T), color="0.3", lw=1)
    ax.quiver(*view(turn[-2]), *(view(turn[-1]) - view(turn[-2])) * 3, color="0.3", arrow_length_ratio=0.9)
    ax.text(*view([0.3, 0.75, -0.3]), "theta (about -j0)", fontsize=8, color="0.3")
    root = np.array([R, 0.0, 0.0])
    beam = np.array([root, root + [1.6, 0, 0]])
    ax.plot(*view(beam.T), color="C0", lw=7, alpha=0.3)
    ax.text(*view(root + [1.0, -0.12, 0.0]), "beam at psi = 0", fontsize=9, color="C0")
    ax.text(*view(root + [0.02, -0.14, 0.0]), "root: the hinge", fontsize=8)
    named = {"a": ([1, 0, 0], "C3", "pitch = -a", [-1, 0, 0]), "b": ([0, 1, 0], "C2", "lag = +b", [0, 1, 0]),
             "c": ([0, 0, 1], "C1", "flap = +c", [0, 0, 1])}
    for name, (d, color, label, about) in named.items():
        d = np.array(d, dtype=float)
        tip = root + 0.7 * d
        ax.quiver(*view(root), *(view(tip) - view(root)), color=color, arrow_length_ratio=0.12, lw=2.2)
        ax.text(*view(root + 0.78 * d), name, color=color, fontsize=13, weight="bold")
        # the positive sense of the named axis: an arc about it, near the arrow's tip
        about = np.array(about, dtype=float)
        u = np.cross(about, [0.2, 0.6, 0.77])
        u /= np.linalg.norm(u)
        w = np.cross(about, u)
        centre = root + 0.5 * d
        arc = np.array([centre + 0.12 * (np.cos(s) * u + np.sin(s) * w) for s in np.linspace(0, 1.6 * np.pi, 30)])
        ax.plot(*view(arc.T), color=color, lw=1.6)
        ax.quiver(*view(arc[-2]), *(view(arc[-1]) - view(arc[-2])) * 3, color=color, arrow_length_ratio=0.9)
        ax.text(*view(centre + 0.2 * u + 0.05 * d), label, color=color, fontsize=9)
    ax.text(*view([0.0, -0.25, 0.0]), "O", fontsize=9)
    ax.set_xlim(-0.4, 2.0)
    ax.set_ylim(-1.0, 1.0)
    ax.set_zlim(-0.3, 1.2)
    ax.set_box_aspect((2.4, 2.0, 1.5))
    ax.set_axis_off()
    ax.view_init(elev=18, azim=-35)
    ax.set_title("The joint frame (a, b, c) at a beam's root on the hub (no precone)\n"
                 "c = a x b points where the hub turns the root; arcs: each named axis's positive sense",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(OUT / "joint_frame.png", dpi=110)
    plt.close(fig)


def articulated():
    sc, traj, ds = run("articulated")
    t = ds["time"].values
    panels(ds, [
        ("hub speed (rad/s)", [("", ds["hub_omega"], "k-")]),
        ("hinge angles (deg)", [("flap", np.degrees(ds["hinge_flap"]), "C1-"),
                                ("lag", np.degrees(ds["hinge_lag"]), "C2-")]),
        ("lag damper and spring (N m)", [("", ds["hinge_torque_lag"], "C2-")]),
        ("drive torque (N m)", [("", ds["drive_torque"], "k-")]),
    ], OUT / "example_articulated.png", "articulated: four hinged blades spun up to 40 rad/s")
    e = ds["energy_total"] + ds["energy_dissipated"] - ds["energy_drive"]
    print(f"  droop at rest {np.degrees(float(ds['hinge_flap'][0])):.2f} deg, coning at 40 rad/s "
          f"{np.degrees(float(ds['hinge_flap'][-1])):.2f} deg; largest lag "
          f"{np.degrees(float(ds['hinge_lag'].max())):.1f} "
          f"deg at t = {float(t[int(np.argmax(ds['hinge_lag'].values))]):.2f} s; drive torque peak "
          f"{float(ds['drive_torque'].max()):.2f} N m; total + dissipated - drive within "
          f"{float(abs(e - e[0]).max()):.3g} J of {float(ds['energy_drive'][-1]):.5g} J of drive work")
    from hubbeam.studies.campbell import campbell
    from hubbeam import plots

    # on a driven hub the four blades are uncoupled and each frequency comes four times: the diagram
    # of one blade shows them once (and keeps the branches of equal frequencies from swapping)
    from hubbeam.io.scenario import validate

    one = sc.to_dict()
    one["beams"] = one["beams"][:1]
    one["sensors"] = []
    speeds = np.linspace(0.0, 40.0, 9)
    camp = campbell(validate(one), speeds, count=4, formulations=("ancf",))
    plots.plot_campbell(camp, OUT / "campbell_articulated.png", title="Campbell diagram: articulated (one blade)")
    f = camp["frequency_hz"].sel(formulation="ancf")
    labels = camp["label"].sel(formulation="ancf")
    for omega in (0.0, 20.0, 40.0):
        row = f.sel(omega=omega).values
        lab = labels.sel(omega=omega).values
        print(f"  Omega = {omega:g} rad/s: " + ", ".join(f"{v:.3f} Hz {label}" for v, label in zip(row, lab)))
    m, L, e_off = 2700.0 * 0.9 * 0.08 * 0.006, 0.9, 0.1
    inertia = m * L**2 / 3
    for omega in (20.0, 40.0):
        flap = np.sqrt(omega**2 * (1 + 1.5 * e_off / L) + 40.0 / inertia) / (2 * np.pi)
        lag = np.sqrt(omega**2 * 1.5 * e_off / L + 2.0 / inertia) / (2 * np.pi)
        print(f"  rigid blade at {omega:g} rad/s: flap {flap:.3f} Hz, lag {lag:.3f} Hz; lag damper zeta "
              f"{2.0 / (2 * inertia * 2 * np.pi * lag):.3f}")


def deploy():
    sc, traj, ds = run("deploy")
    t = ds["time"].values
    (latch,) = traj.latches
    panels(ds, [
        ("hinge angle (deg)", [("", np.degrees(ds["hinge_angle"]), "k-")]),
        ("hinge torque (N m)", [("", ds["hinge_torque"], "C3-")]),
        ("bus rate (mrad/s)", [("about the hinge line (y)", 1e3 * ds["bus_rate_y"], "C0-")]),
        ("panel tip, tangential (mm)", [("", 1e3 * ds["tip_tangential"], "C2-")]),
    ], OUT / "example_deploy.png", f"deploy: a panel swings out from a free bus and latches at t = {latch.time:g} s")
    before = ds.time < latch.time
    print(f"  latch at t = {latch.time:.3f} s, angle {np.degrees(latch.angle):.3f} deg, impulse {latch.impulse:.4f} "
          f"N m s, {latch.energy:.4f} J removed of {latch.kinetic_before:.4f} J of kinetic energy; hinge torque "
          f"{float(ds['hinge_torque'][before][-1]):.3f} N m before, extremes after "
          f"{float(ds['hinge_torque'].min()):.2f} and {float(ds['hinge_torque'].max()):.2f} N m; bus rate before "
          f"{1e3 * float(ds['bus_rate_y'][before][-1]):.3f}"
          f" mrad/s, at the end {1e3 * float(ds['bus_rate_y'][-1]):.4f} mrad/s")
    H = np.sqrt(ds["H_x"] ** 2 + ds["H_y"] ** 2 + ds["H_z"] ** 2)
    e = ds["energy_total"] + ds["energy_dissipated"] - ds["energy_drive"]
    print(f"  |H| about the centre of mass at most {float(H.max()):.3g} N m s; total + dissipated - drive within "
          f"{float(abs(e - e[0]).max()):.3g} J of {float(ds['energy_dissipated'][-1]):.4g} J dissipated")


def arm2():
    sc, traj, ds = run("arm2", state=True)
    t = ds["time"].values
    system = api.build_system(sc)
    ref = {}
    for k, name in ((0, "upper"), (1, "fore")):
        joint = system.beams[k].mount.joint
        ref[name] = np.array([joint.initial_angle[0] + joint.torque.reference(ti)[0] for ti in t])
    # the tip's error: where the forearm's tip is against where a rigid arm at the reference angles puts it
    L1, L2, R = 0.6, 0.6, 0.05

    def tip(a1, a2):  # in the horizontal plane, x radial and z the hub frame's k, a lag turning about +j0
        x = R + L1 * np.cos(a1) + L2 * np.cos(a1 + a2)
        z = -(L1 * np.sin(a1) + L2 * np.sin(a1 + a2))
        return np.array([x, z])

    state = traj.snapshots
    actual = np.array([s.beams[1].centre_line[-1][[0, 2]] for s in state])
    target = tip(ref["upper"], ref["fore"]).T
    error = 1e3 * np.linalg.norm(actual - target, axis=1)
    panels(ds, [
        ("shoulder (rad)", [("angle", ds["shoulder"], "k-"), ("reference", ref["upper"], "C3--")]),
        ("elbow (rad)", [("angle", ds["elbow"], "k-"), ("reference", ref["fore"], "C3--")]),
        ("motor torques (N m)", [("shoulder", ds["shoulder_torque"], "C0-"), ("elbow", ds["elbow_torque"], "C1-")]),
        ("tip error (mm)", [("", error, "C2-")]),
    ], OUT / "example_arm2.png", "arm2: two flexible links, PD motors at shoulder and elbow")
    print(f"  tip error: largest {error.max():.1f} mm at t = {t[int(error.argmax())]:.2f} s, {error[-1]:.1f} mm at "
          f"t = {t[-1]:g} s; shoulder {float(ds['shoulder'][-1]):.4f} rad (reference {ref['upper'][-1]:.4f}), elbow "
          f"{float(ds['elbow'][-1]):.4f} rad (reference {ref['fore'][-1]:.4f})")


if __name__ == "__main__":
    which = set(sys.argv[1:]) or {"frame", "articulated", "deploy", "arm2"}
    for name, draw in (("frame", joint_frame), ("articulated", articulated), ("deploy", deploy), ("arm2", arm2)):
        if name in which:
            draw()
