"""``hubbeam static``, ``modes`` and ``linearize``: analyses about an equilibrium."""

from __future__ import annotations


from hubbeam.cli.common import check_targets, numerical_failure, progress_bar, say, write_jobs

def print_static(d: dict) -> None:
    t = d["tip_displacement"]
    print(f"tip displacement (hub frame): radial {t['radial']:+.6g} m, vertical {t['vertical']:+.6g} m, "
          f"tangential {t['tangential']:+.6g} m")
    print(f"tip position: [{', '.join(f'{v:.6g}' for v in d['tip_position'])}] m")
    print(f"Newton iterations {d['newton_iterations']} over {d['load_steps']} load steps, "
          f"{d['chart_switches']} chart replacements")


def cmd_static(args, scenario) -> dict:
    from hubbeam import api
    from hubbeam.io.targets import Target
    from hubbeam.errors import ComputationError

    targets = check_targets([Target("--plot", getattr(args, "plot", None), "figure")], args)
    try:
        result = api.static(scenario)
    except ComputationError as exc:
        if not str(exc).startswith("static"):
            raise ComputationError(f"static equilibrium: {exc}", partial=exc.partial) from exc
        raise
    d = result.to_dict()
    for note in result.notes:
        say(f"hubbeam: note: {note}")
    if targets:
        from hubbeam import plots

        x0, F0 = result.system.initial_state(0.0)
        sol = result.solution
        title, subtitle = plots.run_title(f"{scenario.name}: static equilibrium", args.overrides)
        write_jobs([(targets[0], lambda p: plots.plot_deformed(result.system, x0, F0, sol.x, sol.chart, p,
                                                               title=title, subtitle=subtitle))])
    if not args.json:
        print_static(d)
    return d


def cmd_modes(args, scenario) -> dict:
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target

    targets = check_targets([Target("--shapes", getattr(args, "shapes", None)),
                      Target("--plot", getattr(args, "plot", None), "figure")], args)
    try:
        result = api.modes(scenario)
        d = result.to_dict()
        ds = result.shapes_dataset() if targets else None
    except ScenarioError:
        raise
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise numerical_failure("modal analysis", exc) from exc

    def figure(path):
        from hubbeam import plots

        half = [0.5 * max(b.section.width, b.section.thickness) for b in result.static.system.beams]
        title, subtitle = plots.run_title(f"{scenario.name}: mode shapes", args.overrides)
        plots.plot_mode_shapes(ds, path, half, title=title, subtitle=subtitle)

    def shapes(path):
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, path)

    write_jobs([(t, figure if t.option == "--plot" else shapes) for t in targets])
    for note in result.static.notes:
        say(f"hubbeam: note: {note}")
    if len(d["frequencies_hz"]) < scenario.analysis.count:
        say(f"hubbeam: note: analysis.count = {scenario.analysis.count}, but the model has only "
             f"{len(d['frequencies_hz'])} (more beam.elements give more)")
    if not args.json:
        print(f"natural frequencies (Hz) about the {d['about']}, {d['rigid_modes']} rigid mode(s) left out:")
        for i, (f, label) in enumerate(zip(d["frequencies_hz"], d["labels"]), 1):
            print(f"  {i:3d}  {f:12.6f}  {label}")
    return d


def cmd_linearize(args, scenario) -> dict:
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target

    targets = check_targets([Target("-o", args.output)], args)
    motors = [b for b in scenario.beam_tables if b.joint is not None and b.joint.torque is not None]
    if args.open_loop and scenario.hub.torque_law is None and not motors and not scenario.controllers:
        raise ScenarioError(f"--open-loop: hub.motion = {scenario.hub.motion!r} has no torque law to leave out (only a "
                            "free hub has one), no joint has a motor ([beams.joint.torque]) and there are no "
                            "[[controllers]]")
    for option, value in (("--reduce", args.reduce), ("--balanced", args.balanced)):
        if value is not None and value < 1:
            raise ScenarioError(f"{option}: must be >= 1 (got {value})")
    if args.fmax is not None and not (np.isfinite(args.fmax) and args.fmax > 0):
        raise ScenarioError(f"--fmax: a frequency > 0 in Hz (got {args.fmax:g})")
    inputs = None if args.inputs is None else [i.strip() for i in args.inputs.split(",")]
    outputs = None if args.outputs is None else [o.strip() for o in args.outputs.split(",")]
    bar = {}

    def progress(done, total):  # the output derivatives: a bar (or a line every 10 s) once the total is known
        if "update" not in bar:
            bar["update"], bar["finish"] = progress_bar(total, "linearize: output derivatives", "evaluations")
        bar["update"](done)

    try:
        model = api.linearize(scenario, inputs, open_loop=args.open_loop, outputs=outputs, reduce=args.reduce,
                              balanced=args.balanced, fmax=args.fmax, progress=progress)
    except ScenarioError as exc:
        text = str(exc)
        for key in ("inputs", "outputs", "reduce", "balanced", "fmax"):
            if text.startswith(f"{key}:"):
                text = f"--{text}"
        raise ScenarioError(text) from None
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise numerical_failure("linearisation", exc) from exc
    finally:
        if "finish" in bar:
            bar["finish"]()
    if targets:
        from hubbeam.io.results import write_netcdf

        write_jobs([(targets[0], lambda p: write_netcdf(model.to_dataset(scenario), p))])
    d = model.to_dict()
    if not args.json:
        reduced = d.get("reduction")
        size = (f"{d['states']} states (reduced from {reduced['full_states']}, {reduced['method']})" if reduced
                else f"{d['states']} states")
        print(f"state space about the {d['about']}: {size}, inputs {', '.join(d['inputs'])}, "
              f"outputs {', '.join(d['outputs']) or '(none: the scenario has no sensors)'}")
        for f, z in list(zip(d["frequencies_hz"], d["damping_ratios"]))[:10]:
            print(f"  {f:12.6f} Hz  damping ratio {z or 0.0:.4g}")  # never "-0"
        if "hankel_singular_values" in d:
            sigma = d["hankel_singular_values"]
            print(f"  Hankel singular values: {', '.join(f'{v:.4g}' for v in sigma[:8])}"
                  f"{f', ... ({len(sigma)})' if len(sigma) > 8 else ''}; H-infinity error bound "
                  f"{reduced['error_bound']:.4g}")
    left_out = [f"outputs left out (not functions of the state, or zero to first order): {', '.join(model.left_out)}"]
    for note in model.notes + (left_out if model.left_out else []):
        say(f"hubbeam: note: {note}")
    return d
