"""The ``hubbeam`` command line (see docs/scenario.md and docs/reliability.md).

Exit status: 0 success, 2 bad input (one line naming the key or option), 1 failed
computation or failed write (a line saying where and what to try; the results so far are
written), 128 + N when stopped by signal N (130 SIGINT, 143 SIGTERM, 129 SIGHUP; a run
writes its partial trajectory). Output targets are checked before any computation. No
traceback reaches the user unless the environment variable HUBBEAM_DEBUG is set.

Only the standard library is imported at module level: the signal handlers are in place
before numpy, numba or xarray load, so an early Ctrl-C is one line, not a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys

#: a measured file may be larger than a scenario file
MAX_MEASURED_BYTES = 256 * 2**20

#: names this module used to import at its top, still importable from it (loaded on first use)
_LAZY = {"EXAMPLES": "hubbeam.io.examples", "example_text": "hubbeam.io.examples",
         "load_scenario": "hubbeam.io.scenario", "ScenarioError": "hubbeam.errors",
         "ComputationError": "hubbeam.errors"}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'hubbeam.cli' has no attribute {name!r}")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse prints a usage of several lines: one line instead
        _say(f"hubbeam: error: {message} (usage: {self.prog} --help)")
        raise SystemExit(2)


def _parser() -> argparse.ArgumentParser:
    from importlib.metadata import PackageNotFoundError, version

    from hubbeam.io.examples import EXAMPLES

    try:
        installed = version("hubbeam")
    except PackageNotFoundError:  # run from a source tree that is not installed
        from hubbeam import __version__ as installed
    p = _Parser(prog="hubbeam", description="Rotating hub with flexible 3D beams: ANCF with torsion and FFR, "
                                            "several beams, tip bodies, torque laws.")
    p.add_argument("--version", action="version", version=f"hubbeam {installed}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def scenario_cmd(name, help_):
        sp = sub.add_parser(name, help=help_)
        sp.add_argument("scenario", help="scenario file (TOML)")
        sp.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                        help="override one key, dotted path and TOML value (e.g. beam.elements=8)")
        sp.add_argument("--json", action="store_true", help="print one JSON object on stdout")
        return sp

    run = scenario_cmd("run", "run the scenario's analysis")
    run.add_argument("-o", "--output", help="NetCDF result file")
    run.add_argument("--csv", help="CSV result file")
    run.add_argument("--plot", help="figure (PNG, PDF, SVG, ...)")
    run.add_argument("--state", action="store_true", help="also store the hub angle and every beam's geometry in the "
                                                          "NetCDF file (-o), for animate and vtk")
    run.add_argument("--plot-vars", metavar="A,B,...",
                     help="variables (or sensors) to draw with --plot (default: every one that is not zero throughout)")
    st = scenario_cmd("static", "static equilibrium under gravity and loads (hub held at theta = 0)")
    st.add_argument("--plot", help="figure of the deformed beam")
    mod = scenario_cmd("modes", "natural frequencies about the static equilibrium (steady rotation for a constant drive)")
    mod.add_argument("--shapes", help="NetCDF file of the mode shapes (docs/modes.md)")
    mod.add_argument("--plot", help="figure of the lowest mode shapes along the span")
    lin = scenario_cmd("linearize", "state space (A, B, C, D) about the equilibrium (steady rotation for a "
                                    "constant drive)")
    lin.add_argument("-o", "--output", help="NetCDF file of A, B, C, D")
    lin.add_argument("--inputs", help="comma-separated: hub_torque, tip_force:BEAM (default: hub_torque on a free hub, "
                                      "the first beam's tip force on a held one)")
    lin.add_argument("--open-loop", action="store_true", help="leave the scenario's hub torque law out")
    camp = scenario_cmd("campbell", "natural frequencies about the steadily rotating state against hub speed")
    camp.add_argument("--omega", required=True, metavar="START:STOP:N", help="hub speeds (rad/s)")
    camp.add_argument("--count", type=int, default=6, help="modes per speed (default 6)")
    camp.add_argument("-o", "--output", help="figure")
    camp.add_argument("--data", help="NetCDF file of the frequencies")
    camp.add_argument("--formulations", default="ancf,ffr,ffr+", help="comma-separated: ancf, ffr, ffr+ (default all)")
    zoom = camp.add_mutually_exclusive_group()
    zoom.add_argument("--fmax", type=float, help="draw frequencies from 0 to FMAX Hz only")
    zoom.add_argument("--frange", metavar="LO:HI", help="draw frequencies from LO to HI Hz only")
    sw = scenario_cmd("sweep", "run the scenario over the cartesian product of varied keys, on Dask")
    sw.add_argument("--vary", action="append", required=True, metavar="KEY=START:STOP:N",
                    help="a varied key and its values (numpy.linspace); repeat for more keys")
    sw.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    sw.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: all cores)")
    sw.add_argument("-o", "--output", required=True, help="NetCDF file of the merged results")
    sw.add_argument("--plot", help="figure of the results (up to four variables)")
    idf = scenario_cmd("identify", "fit scenario parameters to a measured time series (least squares)")
    idf.add_argument("measured", help="CSV with a header row: a 'time' column (s) and the signal's column")
    idf.add_argument("--fit", nargs="+", required=True, metavar="KEY", help="scenario keys to fit (e.g. damping.linear)")
    idf.add_argument("--signal", default="strain_P1", help="the sensor (column) to match (default strain_P1)")
    idf.add_argument("-o", "--output", help="figure of fit and data")
    app = sub.add_parser("applicability", help="map FFR's error against ANCF over deflection and hub speed")
    app.add_argument("scenario", nargs="?", default=None, help="scenario file (default: the bundled exp1)")
    app.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    app.add_argument("--thickness", default="0.001:0.004:7", metavar="START:STOP:N", help="plate thickness (m)")
    app.add_argument("--ratio", default="0:0.6:7", metavar="START:STOP:N", help="hub speed / first natural frequency")
    app.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    app.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: all cores)")
    app.add_argument("-o", "--output", required=True, help="directory for applicability.png, .nc and .md")
    app.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    rep = sub.add_parser("reproduce", help="rerun the paper's tables and figures (Secs. 5 and 6)")
    rep.add_argument("-o", "--output", required=True, help="directory for report.md, tables.json and figures")
    rep.add_argument("--quick", action="store_true", help="experiment 2 at dt = 5 ms (same physics; < 10 min on 2 cores)")
    rep.add_argument("--jobs", type=int, default=None, help="parallel runs (default: all cores)")
    an = sub.add_parser("animate", help="the hub and beams of a run stored with --state in 3D, as GIF or MP4")
    an.add_argument("result", help="NetCDF file of hubbeam run -o OUT.nc --state")
    an.add_argument("-o", "--output", required=True, help="movie file: .gif, or .mp4 (needs ffmpeg: the extra 'video')")
    an.add_argument("--color", default="strain", help="strain (upper surface, default), deflection or none")
    an.add_argument("--stride", type=int, default=1, help="draw every N-th stored output time (default 1)")
    an.add_argument("--fps", type=float, default=20.0, help="frames per second of the movie (default 20)")
    an.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    vt = sub.add_parser("vtk", help="a run stored with --state as a ParaView time series (.pvd and .vtu files)")
    vt.add_argument("result", help="NetCDF file of hubbeam run -o OUT.nc --state")
    vt.add_argument("-o", "--output", required=True, help="directory for NAME.pvd and NAME_NNNNN.vtu")
    vt.add_argument("--force", action="store_true", help="replace a series of the same name already in the directory")
    vt.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    ex = sub.add_parser("example", help="print a bundled scenario")
    ex.add_argument("name", help=f"one of: {', '.join(EXAMPLES)}")
    return p


# ------------------------------------------------------------------------------ helpers
def _say(text: str) -> None:
    """One line on stderr (a closed terminal, after SIGHUP, is not an error)."""
    try:
        print(" ".join(str(text).split()), file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


def _load(args):
    """The scenario of a command: the file checked (a regular text file of sane size), then
    read, overridden and validated."""
    from hubbeam.io.scenario import load_example, load_scenario, table_files
    from hubbeam.io.targets import check_input_file

    dropped: list[str] = []
    if args.scenario is None:  # applicability's default
        scenario = load_example("exp1", args.overrides, dropped)
    else:
        scenario = load_scenario(check_input_file(args.scenario, "scenario file"), args.overrides, dropped)
    for line in dropped:
        _say(f"hubbeam: note: {line}")
    args.tables = [(f"table of {key}", path) for _, key, path in table_files(scenario)]
    return scenario


def _check(targets, args, *inputs):
    """Check the output targets before computing (ScenarioError naming the option); the
    scenario file and the CSV tables it reads are inputs that no target may overwrite."""
    from hubbeam.io.targets import check_outputs

    files = [("scenario file", getattr(args, "scenario", None))] + getattr(args, "tables", []) + list(inputs)
    return check_outputs(targets, files)


def _written(paths) -> str:
    return ", ".join(str(p) for p in paths)


def _write(jobs, interruptible: bool = False) -> list[str]:
    """Write (target, writer) jobs; OutputError (exit 1) naming the ones that failed and the
    ones written; a signal during the writes takes effect after them (``interruptible``: at
    once, for writers that are the computation itself, see io.targets.write_all)."""
    from hubbeam import interrupt
    from hubbeam.io.targets import OutputError, write_all

    written, errors = write_all(jobs, interruptible)
    if errors:
        also = f" (written: {_written(written)})" if written else ""
        raise OutputError("; ".join(errors) + also)
    interrupt.raise_pending()
    return written


def _limit_workers(value, option: str) -> None:
    from hubbeam.io.scenario import ScenarioError

    if value is None:
        return
    cores = os.cpu_count() or 1
    if value < 1:
        raise ScenarioError(f"{option}: must be >= 1 (got {value})")
    if value > 4 * cores:
        raise ScenarioError(f"{option}: {value} processes on {cores} cores; at most {4 * cores}")


def _json_safe(obj, path: str = "", bad: list | None = None):
    """``obj`` with every non-finite float replaced by None (JSON has no NaN); their paths
    are appended to ``bad``."""
    import numpy as np

    if isinstance(obj, dict):
        return {k: _json_safe(v, f"{path}.{k}" if path else str(k), bad) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_safe(v, f"{path}[{i}]", bad) for i, v in enumerate(obj)]
    if isinstance(obj, np.ndarray):
        return _json_safe(obj.tolist(), path, bad)
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        if not math.isfinite(obj):
            if bad is not None:
                bad.append(path)
            return None
        return float(obj)
    return obj


def _print_json(result: dict) -> None:
    bad: list[str] = []
    safe = _json_safe(result, "", bad)
    if bad:
        safe["non_finite"] = {"paths": bad, "reason": "these values are not finite numbers (NaN or infinity); "
                                                      "JSON has none, so they are null"}
    print(json.dumps(safe, allow_nan=False))


# ------------------------------------------------------------------------------ commands
def _print_static(d: dict) -> None:
    t = d["tip_displacement"]
    print(f"tip displacement (hub frame): radial {t['radial']:+.6g} m, vertical {t['vertical']:+.6g} m, "
          f"tangential {t['tangential']:+.6g} m")
    print(f"tip position: [{', '.join(f'{v:.6g}' for v in d['tip_position'])}] m")
    print(f"Newton iterations {d['newton_iterations']} over {d['load_steps']} load steps, "
          f"{d['chart_switches']} chart replacements")


def _cmd_static(args, scenario) -> dict:
    from hubbeam import api
    from hubbeam.io.targets import Target
    from hubbeam.errors import ComputationError

    targets = _check([Target("--plot", getattr(args, "plot", None), "figure")], args)
    try:
        result = api.static(scenario)
    except ComputationError as exc:
        if not str(exc).startswith("static"):
            raise ComputationError(f"static equilibrium: {exc}", partial=exc.partial) from exc
        raise
    d = result.to_dict()
    if targets:
        from hubbeam import plots

        x0, F0 = result.system.initial_state(0.0)
        sol = result.solution
        _write([(targets[0], lambda p: plots.plot_deformed(result.system, x0, F0, sol.x, sol.chart, p,
                                                          title=f"{scenario.name}: static equilibrium"))])
    if not args.json:
        _print_static(d)
    return d


def _numerical_failure(what: str, exc: BaseException):
    """A ComputationError for a linear-algebra failure (a matrix with NaN, not positive
    definite) inside ``what``."""
    from hubbeam.errors import ComputationError

    reason = (str(exc).splitlines() or [""])[0][:160]
    return ComputationError(f"{what} failed ({exc.__class__.__name__}: {reason}); try more analysis.load_steps or "
                            "beam.elements, and check the scenario's values and units (SI)")


def _cmd_modes(args, scenario) -> dict:
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target

    targets = _check([Target("--shapes", getattr(args, "shapes", None)),
                      Target("--plot", getattr(args, "plot", None), "figure")], args)
    try:
        result = api.modes(scenario)
        d = result.to_dict()
        ds = result.shapes_dataset() if targets else None
    except ScenarioError:
        raise
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise _numerical_failure("modal analysis", exc) from exc

    def figure(path):
        from hubbeam import plots

        half = [0.5 * max(b.section.width, b.section.thickness) for b in result.static.system.beams]
        plots.plot_mode_shapes(ds, path, half, title=f"{scenario.name}: mode shapes")

    def shapes(path):
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, path)

    _write([(t, figure if t.option == "--plot" else shapes) for t in targets])
    if len(d["frequencies_hz"]) < scenario.analysis.count:
        _say(f"hubbeam: note: analysis.count = {scenario.analysis.count}, but the model has only "
             f"{len(d['frequencies_hz'])} (more beam.elements give more)")
    if not args.json:
        print(f"natural frequencies (Hz) about the {d['about']}, {d['rigid_modes']} rigid mode(s) left out:")
        for i, (f, label) in enumerate(zip(d["frequencies_hz"], d["labels"]), 1):
            print(f"  {i:3d}  {f:12.6f}  {label}")
    return d


def _cmd_linearize(args, scenario) -> dict:
    import numpy as np

    from hubbeam import api
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target

    targets = _check([Target("-o", args.output)], args)
    if args.open_loop and scenario.hub.torque_law is None:
        raise ScenarioError(f"--open-loop: hub.motion = {scenario.hub.motion!r} has no torque law to leave out (only a "
                            "free hub has one)")
    inputs = None if args.inputs is None else [i.strip() for i in args.inputs.split(",")]
    try:
        model = api.linearize(scenario, inputs, open_loop=args.open_loop)
    except ScenarioError as exc:
        raise ScenarioError(f"--{exc}" if str(exc).startswith("inputs:") else str(exc)) from None
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise _numerical_failure("linearisation", exc) from exc
    if targets:
        from hubbeam.io.results import write_netcdf

        _write([(targets[0], lambda p: write_netcdf(model.to_dataset(scenario), p))])
    d = model.to_dict()
    if not args.json:
        print(f"state space about the {d['about']}: {d['states']} states, inputs {', '.join(d['inputs'])}, "
              f"outputs {', '.join(d['outputs']) or '(none: the scenario has no sensors)'}")
        for f, z in list(zip(d["frequencies_hz"], d["damping_ratios"]))[:10]:
            print(f"  {f:12.6f} Hz  damping ratio {z:.4g}")
    left_out = [f"outputs left out (not functions of the state, or zero to first order): {', '.join(model.left_out)}"]
    for note in model.notes + (left_out if model.left_out else []):
        _say(f"hubbeam: note: {note}")
    return d


def _cmd_run(args, scenario) -> dict:
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target

    kind = scenario.analysis.kind
    if kind != "dynamic":
        refused = [("-o", args.output), ("--csv", args.csv), ("--state", args.state or None),
                   ("--plot-vars", args.plot_vars)] + \
            ([("--plot", args.plot)] if kind == "modes" else [])
        for option, value in refused:
            if value is not None:
                raise ScenarioError(f"{option}: analysis.kind = {kind!r} gives no time series to write (only a dynamic "
                                    f"analysis does); for the {kind} result use --json")
        return _cmd_static(args, scenario) if kind == "static" else _cmd_modes(args, scenario)
    from hubbeam import api, limits
    from hubbeam.interrupt import Interrupted

    targets = _check([Target("-o", args.output), Target("--csv", args.csv), Target("--plot", args.plot, "figure")],
                     args)
    if args.state and args.output is None:
        raise ScenarioError("--state: the state is stored in the NetCDF file; give -o OUT.nc")
    if args.plot is not None and not scenario.sensors:
        raise ScenarioError(f"--plot {args.plot}: the scenario has no sensors, so there is nothing to draw")
    plot_vars = _plot_vars(args.plot_vars, args.plot, scenario)
    try:
        size = limits.check_run(scenario, state=args.state)
    except ScenarioError as exc:
        if not args.state:
            raise
        limits.check_run(scenario)  # too large without the state too: that error as it is
        raise ScenarioError(f"--state: {exc} (the recorded state adds {limits.state_values(scenario)} numbers per "
                            "output time; fewer beam elements need fewer)") from None
    if size.note:
        _say(f"hubbeam: note: {size.note}")
    for line in api.reduction_warnings(scenario):
        _say(f"hubbeam: warning: {line}")
    progress, finish = _progress_bar(scenario.analysis.t_end)
    try:
        traj, failure = api.run(scenario, progress, state=args.state)
    except Interrupted as exc:
        traj, failure = exc.partial, exc
    finally:
        finish()
    _finish_run(targets, scenario, traj, failure, plot_vars)
    final = {name: values[-1] for name, values in traj.records.items()}
    summary = {"steps": traj.steps, "newton_iterations": traj.newton_iterations,
               "newton_iterations_per_step": traj.newton_iterations / max(traj.steps, 1),
               "lu_factorisations": traj.factorisations,
               "wall_time_s": traj.wall_time_s, "chart_switches": traj.chart_switches, "final": final}
    if not args.json:
        print(f"{traj.steps} steps, {summary['newton_iterations_per_step']:.2f} Newton iterations per step, "
              f"{traj.wall_time_s:.2f} s of integration")
        for name, value in final.items():
            if isinstance(value, dict):
                value = ", ".join(f"{k} {v:+.6g}" for k, v in value.items())
            else:
                value = f"{value:+.6g}"
            print(f"  {name} at t = {traj.times[-1]:g} s: {value}")
    return summary


def _plot_vars(text, plot, scenario) -> list[str] | None:
    """The variables ``--plot-vars`` names (a sensor stands for all its columns); ScenarioError
    naming an unknown one, or the option without --plot."""
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.sensors import columns

    if text is None:
        return None
    if plot is None:
        raise ScenarioError("--plot-vars: needs --plot (the figure to draw them in)")
    known = {s.name: columns(s) for s in scenario.sensors}
    known.update({c: [c] for cols in list(known.values()) for c in cols})
    chosen = []
    for name in (n.strip() for n in text.split(",")):
        if name not in known:
            raise ScenarioError(f"--plot-vars: unknown variable {name!r} (this run has: {', '.join(known)})")
        chosen += [c for c in known[name] if c not in chosen]
    return chosen


def _finish_run(targets, scenario, traj, failure, plot_vars=None) -> None:
    """Write a run's results (complete or partial) and raise its failure with one line that
    says how far it got and what was written."""
    from hubbeam import interrupt
    from hubbeam.interrupt import Interrupted
    from hubbeam.io import results
    from hubbeam.io.targets import OutputError, write_all
    from hubbeam.errors import ComputationError

    has_data = traj is not None and len(traj.times) > 0
    status = None
    if failure is not None and has_data:
        reason = f"interrupted by {failure.name}" if isinstance(failure, Interrupted) else f"computation failed: {failure}"
        status = results.completion(traj, scenario.analysis.t_end, reason)
    cache = {}

    def dataset():
        if "ds" not in cache:
            cache["ds"] = results.to_dataset(traj, scenario, status)
        return cache["ds"]

    def plot(path):
        from hubbeam import plots

        chosen, title = plot_vars, scenario.name + (" (partial)" if status else "")
        if chosen is None and not plots.timeseries_panels(dataset(), None):  # all zero: that is the result to draw
            chosen, title = list(dataset().data_vars), title + ": every variable is zero throughout"
        plots.plot_timeseries(dataset(), path, title=title, variables=chosen)

    writers = {"-o": lambda p: results.write_trajectory_netcdf(traj, scenario, p, status),
               "--csv": lambda p: results.write_csv(dataset(), p), "--plot": plot}
    jobs = [(t, writers[t.option]) for t in targets] if has_data else []
    written, errors = write_all(jobs)
    t_reached = float(traj.times[-1]) if has_data else None
    not_written = f"; could not write: {'; '.join(errors)}" if errors else ""
    if isinstance(failure, Interrupted):
        interrupt.take_pending()  # a second signal while writing: we are stopping anyway
        if t_reached is None:
            failure.detail = " before the time integration started; nothing written"
        else:
            where = f" at t = {t_reached:g} s of {scenario.analysis.t_end:g} s"
            what = (f"; the results so far are in {_written(written)} (marked partial)" if written
                    else "; no output file was requested, nothing written" if not targets else "")
            failure.detail = where + what + not_written
        raise failure
    if failure is not None:
        text = str(failure)
        if has_data and " at t = " not in text:
            text = f"time integration after t = {t_reached:g} s: {text}"
        if written:
            text += f" Results up to t = {t_reached:g} s are in {_written(written)} (marked partial)."
        raise ComputationError(text + not_written, partial=traj) from failure
    if errors:
        raise OutputError("; ".join(errors) + (f" (written: {_written(written)})" if written else ""))
    interrupt.raise_pending()


def _cmd_campbell(args, scenario) -> dict:
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target
    from hubbeam.studies.variants import FORMULATIONS, parse_range

    speeds = parse_range(args.omega, "--omega")
    if (speeds < 0).any():
        raise ScenarioError("--omega: hub speeds must be >= 0")
    if not 1 <= args.count <= 50:
        raise ScenarioError(f"--count: must be between 1 and 50 (got {args.count})")
    forms = tuple(f.strip() for f in args.formulations.split(","))
    unknown = [f for f in forms if f not in FORMULATIONS]
    if unknown:
        raise ScenarioError(f"--formulations: unknown {', '.join(unknown)} (use {', '.join(FORMULATIONS)})")
    if len(set(forms)) != len(forms):
        raise ScenarioError(f"--formulations: a formulation is given twice ({args.formulations})")
    frange = None if args.fmax is None else (0.0, args.fmax)
    if args.frange is not None:
        try:
            frange = tuple(float(v) for v in args.frange.split(":"))
        except ValueError:
            frange = ()
    if frange is not None and not (len(frange) == 2 and all(map(math.isfinite, frange)) and 0 <= frange[0] < frange[1]):
        option = "--fmax" if args.fmax is not None else "--frange"
        raise ScenarioError(f"{option}: expected {'a finite FMAX > 0' if args.fmax is not None else 'LO:HI with 0 <= LO < HI'}"
                            f" (Hz; got {args.fmax if args.fmax is not None else args.frange!r})")
    if frange is not None and args.output is None:
        raise ScenarioError(f"{'--fmax' if args.fmax is not None else '--frange'}: zooms the figure, and no figure is "
                            "asked for (give -o FIG.png)")
    targets = _check([Target("-o", args.output, "figure"), Target("--data", args.data)], args)
    from hubbeam.studies.campbell import campbell

    progress, finish = _progress_bar(len(forms) * speeds.size, label="campbell", unit="points")
    try:
        ds = campbell(scenario, speeds, count=args.count, formulations=forms,
                      progress=lambda done, total: progress(done))
    finally:
        finish()

    def figure(path):
        from hubbeam import plots

        plots.plot_campbell(ds, path, title=f"Campbell diagram: {scenario.name}", frange=frange)

    def data(path):
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, path)

    _write([(t, figure if t.option == "-o" else data) for t in targets])
    import numpy as np

    short = {f: int(np.isfinite(ds["tracked_frequency_hz"].sel(formulation=f).values).any(axis=0).sum()) for f in forms}
    short = {f: n for f, n in short.items() if n < args.count}
    if short:
        _say(f"hubbeam: note: --count {args.count}, but the model has only "
             f"{', '.join(f'{n} modes with {f}' for f, n in short.items())} (the others are null; more beam.elements "
             "give more)")
    if frange is not None and targets and targets[0].option == "-o":
        f = ds["frequency_hz"].values
        f = f[np.isfinite(f)]
        if f.size and not ((f >= frange[0]) & (f <= frange[1])).any():
            _say(f"hubbeam: note: {'--fmax' if args.fmax is not None else '--frange'}: no frequency lies in "
                 f"{frange[0]:g} to {frange[1]:g} Hz (they span {f.min():.4g} to {f.max():.4g} Hz), so the figure shows "
                 "only the speed lines")
    result = {"omega": speeds.tolist(),
              "frequencies_hz": {str(f): ds["frequency_hz"].sel(formulation=f).values.tolist() for f in forms},
              "labels": {str(f): ds["label"].sel(formulation=f).values.tolist() for f in forms},
              "tracked": {str(f): {"frequencies_hz": ds["tracked_frequency_hz"].sel(formulation=f).values.tolist(),
                                   "labels": ds["branch_label"].sel(formulation=f).values.tolist(),
                                   "mac": ds["mac"].sel(formulation=f).values.tolist()} for f in forms}}
    if not args.json:
        for f in forms:
            first = ds["frequency_hz"].sel(formulation=f).values[:, 0]
            print(f"{f:5s} first mode: {first[0]:.4f} Hz at {speeds[0]:g} rad/s -> {first[-1]:.4f} Hz at {speeds[-1]:g} rad/s")
    return result


#: a sweep has at most this many points
MAX_SWEEP_POINTS = 100_000


def _cmd_sweep(args, scenario) -> dict:
    import itertools

    import numpy as np

    from hubbeam.interrupt import Interrupted
    from hubbeam.io.scenario import ScenarioError, apply_overrides, validate
    from hubbeam.io.targets import Target
    from hubbeam.studies.sweep import format_value, sweep
    from hubbeam.studies.variants import parse_vary

    varied = {}
    for text in args.vary:
        key, values, integral = parse_vary(text)
        if key in varied:
            raise ScenarioError(f"--vary {key}: given twice (give one range per key)")
        varied[key] = (values, integral)
    _limit_workers(args.workers, "--workers")
    total = int(np.prod([len(v[0]) for v in varied.values()], dtype=float))
    if total > MAX_SWEEP_POINTS:
        raise ScenarioError(f"--vary: {total} points; at most {MAX_SWEEP_POINTS}")
    # every corner of the ranges is validated here (first and last value of each key, so the
    # extremes of steps and memory too): a bad key or value is a clear error, not a sweep of failures
    from hubbeam.limits import check_magnitudes, check_run

    for corner in itertools.product(*[sorted({0, len(v[0]) - 1}) for v in varied.values()]):
        overrides = [f"{k}={format_value(v[0][i], v[1])}" for (k, v), i in zip(varied.items(), corner)]
        try:
            point = validate(apply_overrides(scenario.to_dict(), overrides))
            check_magnitudes(point)
            if point.analysis.kind == "dynamic":
                check_run(point)
        except ScenarioError as exc:
            raise ScenarioError(f"--vary: at {', '.join(overrides)} (a corner of the ranges): {exc}") from None
    targets = _check([Target("-o", args.output), Target("--plot", args.plot, "figure")], args)
    progress, finish = _progress_bar(total, label="sweep", unit="points")
    partial = None
    try:
        ds = sweep(scenario, varied, scheduler=args.scheduler, workers=args.workers,
                   progress=lambda done, n: progress(done))
    except Interrupted as exc:
        ds, partial = exc.partial, exc
    finally:
        finish()
    if ds is None:
        partial.detail = "; no point had finished, nothing written"
        raise partial
    ds.attrs["scenario_toml"] = json.dumps(scenario.to_dict())

    def data(path):
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, path)

    def figure(path):
        from hubbeam import plots

        if not [n for n in ds.data_vars if n not in ("failed", "message") and ds[n].dtype.kind == "f"]:
            raise ValueError("nothing to plot: no point produced a result")
        plots.plot_sweep(ds, path, title=f"sweep of {scenario.name} over {', '.join(varied)}")

    jobs = [(t, data if t.option == "-o" else figure) for t in targets]
    if partial is not None:
        from hubbeam import interrupt
        from hubbeam.io.targets import write_all

        written, errors = write_all(jobs)
        interrupt.take_pending()
        done = ds.attrs.get("points_done", 0)
        partial.detail = (f" after {done} of {total} points; " +
                          (f"the results so far are in {_written(written)} (marked partial; the points not run "
                           "are marked failed)" if written else "nothing written") +
                          (f"; could not write: {'; '.join(errors)}" if errors else ""))
        raise partial
    _write(jobs)
    failed = int(ds["failed"].sum())
    if not args.json:
        print(f"{total} points ({failed} failed) -> {args.output}")
    return {"points": total, "failed": failed, "output": args.output, "dims": dict(ds.sizes)}


def _read_measured(path: str, signal: str):
    """(times, values) of the measured file's 'time' and ``signal`` columns; ScenarioError
    naming the file, column and row for anything that is not a clean, increasing series."""
    import pandas as pd

    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import check_input_file
    from hubbeam.studies.identify import check_measured

    check_input_file(path, "measured file", MAX_MEASURED_BYTES)
    try:
        table = pd.read_csv(path)
    except Exception as exc:
        reason = (str(exc).splitlines() or [exc.__class__.__name__])[0][:160]
        raise ScenarioError(f"{path}: cannot read as CSV ({reason})") from None
    for column in ("time", signal):
        if column not in table.columns:
            raise ScenarioError(f"{path}: no column {column!r} (columns: {', '.join(map(str, table.columns))})")
    arrays = []
    for column in ("time", signal):
        raw = table[column]
        values = pd.to_numeric(raw, errors="coerce")
        bad = values.isna().to_numpy()
        if bad.any():
            i = int(bad.argmax())
            raise ScenarioError(f"{path}: column {column!r}, row {i + 2}: not a number ({raw.iloc[i]!r})")
        arrays.append(values.to_numpy(float))
    return check_measured(arrays[0], arrays[1], what=path, labels=("time", signal), first_row=2)


def _cmd_identify(args, scenario) -> dict:
    import numpy as np

    from hubbeam.io.targets import Target
    from hubbeam.studies.identify import identify

    targets = _check([Target("-o", args.output, "figure")], args, ("measured file", args.measured))
    times, measured = _read_measured(args.measured, args.signal)
    progress, _ = _progress_bar(None, label="identify", unit="simulations")
    fit = identify(scenario, times, measured, args.fit, signal=args.signal, progress=progress)
    d = fit.to_dict()
    if targets:
        from hubbeam import plots

        _write([(targets[0], lambda p: plots.plot_fit(fit.times, fit.measured, fit.fitted, p, args.signal,
                                                      title=f"{scenario.name}: fit of {', '.join(args.fit)}"))])
    if not args.json:
        for name, p in d["parameters"].items():
            ci = "n/a" if p["ci95"] is None else f"{p['ci95']:.3g}"
            print(f"{name} = {p['value']:.6g} +- {ci} (95 %), from {p['initial']:.6g}")
        if len(args.fit) > 1:
            print(f"correlation: {np.array2string(np.array(fit.correlation), precision=3)}")
        print(f"rms residual {d['rms_residual']:.3g}, {d['simulations']} simulations")
        for note in d["notes"]:
            print(f"note: {note}")
    return d


def _cmd_applicability(args) -> dict:
    import time
    from pathlib import Path

    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target
    from hubbeam.studies.applicability import applicability_map
    from hubbeam.studies.variants import parse_range

    scenario = _load(args)
    thickness, ratio = parse_range(args.thickness, "--thickness"), parse_range(args.ratio, "--ratio")
    if (thickness <= 0).any() or (ratio < 0).any() or (ratio >= 1).any():
        raise ScenarioError("--thickness must be > 0 and --ratio in [0, 1)")
    _limit_workers(args.workers, "--workers")
    _check([Target("-o", args.output, "directory")], args)
    from hubbeam.io.targets import check_inside

    check_inside("-o", args.output, [f"applicability.{ext}" for ext in ("png", "nc", "md")])
    total = thickness.size * (ratio.size + 1)
    progress, finish = _progress_bar(total, label="applicability", unit="tasks")
    start = time.perf_counter()
    try:
        ds = applicability_map(scenario, thickness, ratio, scheduler=args.scheduler, workers=args.workers,
                               progress=lambda done, n: progress(done))
    finally:
        finish()
    wall = time.perf_counter() - start
    out = Path(args.output)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        from hubbeam.io.targets import OutputError

        raise OutputError(f"-o {out}: cannot create the directory ({exc.strerror})") from None
    lines = ["| h (mm) | w_m/L | " + " | ".join(f"ω/ω1 = {r:.2f}" for r in ratio) + " |",
             "|---|---|" + "---|" * ratio.size]
    for i, h in enumerate(thickness):
        cells = [f"{ds['frequency_error_pct'].values[i, j]:+.1f} / {ds['deflection_error_pct'].values[i, j]:+.1f}"
                 for j in range(ratio.size)]
        lines.append(f"| {1000 * h:.2f} | {ds['w_m_over_L'].values[i]:.2f} | " + " | ".join(cells) + " |")
    text = (f"# FFR's error against ANCF ({scenario.name})\n\nEach cell: first-frequency error / tip-deflection error "
            f"of FFR in percent. {total} tasks, {wall:.0f} s.\n\n" + "\n".join(lines) + "\n")

    def data(path):
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, path)

    def figure(path):
        from hubbeam import plots

        plots.plot_applicability(ds, path, title=f"FFR against ANCF: {scenario.name}")

    def table(path):
        Path(path).write_text(text, encoding="utf-8")

    _write([(Target("-o", str(out / "applicability.nc")), data), (Target("-o", str(out / "applicability.png")), figure),
            (Target("-o", str(out / "applicability.md")), table)])
    failed = int((ds["message"] != "").sum())
    if not args.json:
        print(f"{total} tasks ({failed} failed) in {wall:.0f} s -> {out}/applicability.png, .nc, .md")
    return {"tasks": total, "failed": failed, "wall_time_s": wall, "output": str(out)}


def _cmd_reproduce(args) -> int:
    import shutil
    import tempfile
    from pathlib import Path

    from hubbeam.io.targets import OutputError, Target
    from hubbeam.reproduce.pipeline import reproduce

    _limit_workers(args.jobs, "--jobs")
    _check([Target("-o", args.output, "directory")], args)
    from hubbeam.io.targets import check_inside

    check_inside("-o", args.output, ["report.md", "tables.json"])

    def progress(done, total, outcome):
        state = "failed" if outcome.failure else "done"
        _say(f"hubbeam: note: reproduce {done} of {total} runs ({100 * done / total:.0f} %): {outcome.case.key} "
             f"{state} in {outcome.wall_time_s:.0f} s")

    out = Path(args.output)
    try:
        out.mkdir(parents=True, exist_ok=True)
        work = Path(tempfile.mkdtemp(prefix=".reproduce-", dir=out))
    except OSError as exc:
        raise OutputError(f"-o {out}: cannot create the directory ({exc.strerror})") from None
    keep = False
    try:
        # the report is written into a scratch directory inside DIR and each file moved into DIR
        # when all are complete, so that a failed write leaves no half report
        try:
            path, _ = reproduce(work, quick=args.quick, jobs=args.jobs, progress=progress)
        except OSError as exc:
            raise OutputError(f"-o {out}: cannot write the report ({exc.strerror or exc})") from None
        from hubbeam import interrupt

        with interrupt.deferred():
            for item in sorted(work.iterdir()):
                try:
                    os.replace(item, out / item.name)
                except OSError as exc:  # the report is complete: keep it where it is, never delete it
                    keep = True
                    raise OutputError(f"-o {out}: cannot move {item.name} into place ({exc.strerror or exc}); the "
                                      f"complete report is kept in {work}") from None
        interrupt.raise_pending()
    finally:
        if not keep:
            shutil.rmtree(work, ignore_errors=True)
    print(f"report: {out / path.name}")
    return 0


def _cmd_animate(args) -> dict:
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.state import read_state
    from hubbeam.io.targets import Target

    movie = os.path.splitext(args.output)[1].lower()
    if movie not in (".gif", ".mp4"):
        raise ScenarioError(f"-o {args.output}: the movie must be a .gif or an .mp4 file")
    if args.stride < 1:
        raise ScenarioError(f"--stride: must be >= 1 (got {args.stride})")
    if not (math.isfinite(args.fps) and 0.01 <= args.fps <= 100):
        raise ScenarioError(f"--fps: must be between 0.01 and 100 (got {args.fps:g})")
    from hubbeam.animate import COLORINGS, animate, find_ffmpeg, frame_indices

    if args.color not in COLORINGS:
        raise ScenarioError(f"--color: unknown {args.color!r} (use {', '.join(COLORINGS)})")
    ffmpeg = find_ffmpeg() if movie == ".mp4" else None
    if movie == ".mp4" and ffmpeg is None:
        raise ScenarioError(f"-o {args.output}: an MP4 needs ffmpeg, which is not installed: pip install "
                            "'hubbeam[video]' (imageio-ffmpeg), or write a .gif")
    targets = _check([Target("-o", args.output)], args, ("result file", args.result))
    state = read_state(args.result, "result file")
    if state.partial:
        _say(f"hubbeam: note: {args.result} holds a partial run: {state.partial}")
    frames = []
    _write([(targets[0], lambda p: frames.append(animate(state, p, args.color, args.stride, args.fps, ffmpeg)))],
           interruptible=True)  # rendering the frames is the computation: a signal stops it, nothing is written
    shown = 100.0 / int(int(1000 / args.fps) / 10)  # a GIF stores whole 1/100 s per frame (Pillow truncates)
    if movie == ".gif" and abs(shown - args.fps) > 0.01 * args.fps:
        _say(f"hubbeam: note: --fps {args.fps:g}: a GIF stores each frame's time in whole 1/100 s, so it plays at "
             f"{shown:.4g} frames per second")
    if not args.json:
        drawn = state.times[frame_indices(state, args.stride)]
        span = f"t = {drawn[0]:g} s" if drawn.size == 1 else f"t = {drawn[0]:g} to {drawn[-1]:g} s"
        print(f"{frames[0]} frame{'' if frames[0] == 1 else 's'} ({span}) -> {args.output}")
    return {"frames": frames[0], "output": args.output}


def _cmd_vtk(args) -> dict:
    import re
    from pathlib import Path

    from hubbeam.io import vtk
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.state import read_state
    from hubbeam.io.targets import OutputError, Target

    _check([Target("-o", args.output, "directory")], args)
    state = read_state(args.result, "result file")
    if state.partial:
        _say(f"hubbeam: note: {args.result} holds a partial run: {state.partial}")
    out = Path(args.output)
    pvd, vtus = vtk.file_names(state)
    pattern = re.compile(re.escape(vtk.series_name(state)) + rf"_\d{{{vtk.INDEX_DIGITS}}}\.vtu")
    old = sorted(p for p in out.iterdir() if p.name == pvd or pattern.fullmatch(p.name)) if out.is_dir() else []
    if old and not args.force:
        raise ScenarioError(f"-o {out}: holds a series named {vtk.series_name(state)!r} already ({old[0].name}"
                            f"{f' and {len(old) - 1} more' if len(old) > 1 else ''}); give another directory or "
                            "--force to replace it")
    from hubbeam.io.targets import check_inside

    check_inside("-o", out, [pvd, *vtus])
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / pvd).unlink(missing_ok=True)  # --force: an old collection must not list the new files mixed with old ones
    except OSError as exc:
        raise OutputError(f"-o {out}: cannot create the directory or remove the old {pvd} ({exc.strerror})") from None
    jobs = [(Target("-o", str(out / name)), lambda p, i=i: vtk.write_vtu(state, i, p)) for i, name in enumerate(vtus)]
    from hubbeam import interrupt
    from hubbeam.io.targets import write_all

    def left(n):
        return (f"{n} of {len(vtus)} time steps: {out} holds " +
                (f"{vtus[0]} to {vtus[n - 1]} but no {pvd} (run again with --force for the whole series)" if n
                 else "none of them"))

    done = 0
    try:
        for start in range(0, len(jobs), 100):  # in chunks: a signal is noticed between them
            written, errors = write_all(jobs[start : start + 100])  # a signal in a chunk takes effect after it
            done += len(written)
            if errors:  # a full disk: the first reason, not one per file
                more = f" (and {len(errors) - 1} more files)" if len(errors) > 1 else ""
                raise OutputError(f"{errors[0]}{more}; after {left(done)}")
            interrupt.raise_pending()
    except interrupt.Interrupted as exc:
        exc.detail = f" after {left(done)}"
        raise
    # the collection last: it never lists a file that is not there
    _write([(Target("-o", str(out / pvd)), lambda p: Path(p).write_text(vtk.pvd_text(state), encoding="utf-8"))])
    for stale in old:  # --force: files of an earlier, longer series
        if stale.name != pvd and stale.name not in vtus:
            stale.unlink(missing_ok=True)
    if not args.json:
        print(f"{len(vtus)} time steps -> {out / pvd}")
    return {"files": len(vtus), "pvd": str(out / pvd)}


def _progress_bar(t_end: float, label: str = "simulating", unit: str = "s"):
    """(update(t), finish()): a rich progress bar on a terminal; in any case ``update`` is
    where a signal whose exception a library swallowed is raised again (interrupt.check)."""

#: seconds between two progress lines when stderr is not a terminal (none before the first interval)
PROGRESS_EVERY = 10.0


def _compile_note() -> None:
    """One line before numba compiles the solver into its on-disk cache (the first run on a machine)."""
    from hubbeam.solvers.compiled_alpha import cache_is_cold

    if cache_is_cold():
        _say("hubbeam: note: compiling the solver for this machine (first run only, about half a minute)")


def _progress_bar(t_end: float | None, label: str = "run", unit: str = "s"):
    """(update(t), finish()): a rich progress bar on a terminal; otherwise a plain line
    ``hubbeam: note: LABEL ...`` every PROGRESS_EVERY seconds from the first report (so a short
    command prints none, even when it compiled first);
    in any case ``update`` is where a signal whose exception a library swallowed is raised
    again (interrupt.check). ``t_end`` None: the total is not known (a count so far)."""
    from hubbeam import interrupt

    if t_end is None or not sys.stderr.isatty():
        import time

        last = [None]  # the clock starts at the first report (not before a first compile)

        def line(done):
            interrupt.check()
            if last[0] is None:
                last[0] = time.monotonic()
            if time.monotonic() - last[0] < PROGRESS_EVERY:
                return
            last[0] = time.monotonic()
            if t_end is None:
                _say(f"hubbeam: note: {label}: {done:g} {unit} so far")
            else:
                where = f"t = {done:.4g} of {t_end:g} s" if unit == "s" else f"{done:g} of {t_end:g} {unit}"
                _say(f"hubbeam: note: {label} {where} ({100 * done / max(t_end, 1e-300):.0f} %)")

        return line, lambda: None
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    done = "t = {task.completed:.2f} s" if unit == "s" else "{task.completed:.0f} / {task.total:.0f} " + unit
    bar = Progress(TextColumn(label), BarColumn(), TextColumn(done),
                   TimeRemainingColumn(), transient=True)
    task = bar.add_task("run", total=t_end)
    bar.start()

    def update(t):
        interrupt.check()
        bar.update(task, completed=t)

    return update, bar.stop


def _where(exc: BaseException) -> str:
    """The function (and module) where an exception was raised."""
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None:
        return "an unknown place"
    code = tb.tb_frame.f_code
    module = tb.tb_frame.f_globals.get("__name__", "?")
    return f"{module}.{code.co_name}"


# ------------------------------------------------------------------------------ main
def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit status. SIGINT, SIGTERM and SIGHUP are handled
    (see :mod:`hubbeam.interrupt`) from here on; the previous handlers come back after it.

    ``argv`` None: the command line of this process (the ``hubbeam`` script, ``python -m
    hubbeam.cli``), which ends after the command. The modules it loads make objects that live
    until the process ends, not garbage: the cyclic garbage collector is off while they load
    and they are then frozen out of it (:func:`gc.freeze`, in :func:`_settled`), and so is
    everything at the end. Otherwise its collections walked numba's and pydantic's objects
    again and again (about 0.2 s of ``hubbeam run benchmarks/case_a.toml`` during the
    command), and Python's last one at exit walked all of them (about 0.3 s after numba had
    loaded its compiled code). Called with a list (tests, scripts), the collector is left alone."""
    import gc

    from hubbeam import interrupt

    program = argv is None
    if program:
        gc.disable()  # until _settled
    try:
        with interrupt.handling():
            return _main(argv, program)
    except interrupt.Interrupted as exc:  # during start-up (imports), before _main could catch it
        _say(f"hubbeam: interrupted by {exc.name}{exc.detail or '; nothing written'}")
        return exc.exit_code
    finally:
        if program:
            gc.freeze()  # the collection at exit then has nothing to walk


def _settled(program: bool) -> None:
    """The command's modules are loaded: in a process that ends after its command (see
    :func:`main`), the objects alive now move into the garbage collector's permanent
    generation and the collector is on again for what the computation makes."""
    if program:
        import gc

        gc.freeze()
        gc.enable()


def _main(argv, program: bool = False) -> int:
    """The command, with the warnings of the libraries it uses (numpy, scipy, matplotlib)
    caught: on success each distinct one is one ``hubbeam: warning:`` line; on failure the
    failure's one line says what matters (a warning is not printed with its source line)."""
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        code = _command(argv, program)
    if code == 0:
        for text in dict.fromkeys(f"{w.category.__name__}: {w.message} ({w.filename.rsplit(os.sep, 1)[-1]}:{w.lineno})"
                                  for w in caught):
            _say(f"hubbeam: warning: {text}")
    return code


def _command(argv, program: bool = False) -> int:
    from hubbeam.interrupt import Interrupted, raise_pending

    args = _parser().parse_args(argv)
    if args.command in ("example", "animate", "vtk"):
        _settled(program)  # these load their modules as they go (matplotlib, h5py)
    from hubbeam.errors import ComputationError, ScenarioError
    from hubbeam.io.examples import example_text
    from hubbeam.io.targets import OutputError

    try:
        if args.command == "example":
            sys.stdout.write(example_text(args.name))
            return 0
        if args.command == "reproduce":
            _compile_note()
            _settled(program)
            return _cmd_reproduce(args)
        if args.command == "applicability":
            _compile_note()
            _settled(program)
            result = _cmd_applicability(args)
        elif args.command in ("animate", "vtk"):
            result = {"animate": _cmd_animate, "vtk": _cmd_vtk}[args.command](args)
        else:
            scenario = _load(args)
            _compile_note()  # imports the solver: numba, scipy.linalg and the model's modules
            _settled(program)
            handler = {"static": _cmd_static, "modes": _cmd_modes, "run": _cmd_run, "campbell": _cmd_campbell,
                       "linearize": _cmd_linearize,
                       "sweep": _cmd_sweep, "identify": _cmd_identify}[args.command]
            result = handler(args, scenario)
        raise_pending()
        if args.json:
            _print_json(result)
        return 0
    except ScenarioError as exc:
        _say(f"hubbeam: error: {exc}")
        return 2
    except OutputError as exc:
        _say(f"hubbeam: cannot write results: {exc}")
        return 1
    except ComputationError as exc:
        _say(f"hubbeam: computation failed: {exc}")
        return 1
    except Interrupted as exc:
        _say(f"hubbeam: interrupted by {exc.name}{exc.detail or '; nothing written'}")
        return exc.exit_code
    except KeyboardInterrupt:
        _say("hubbeam: interrupted")
        return 130
    except BrokenPipeError:  # the reader went away (`hubbeam run ... | head`): stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # so that Python's final flush does not fail again
        return 0
    except ArithmeticError as exc:  # overflow, division by zero: a computation out of the range of doubles
        if os.environ.get("HUBBEAM_DEBUG"):
            raise
        _say(f"hubbeam: computation failed: {exc.__class__.__name__} in {_where(exc)} ({exc}); the scenario's "
             "numbers are out of the range the computation can hold: check its values and units (SI)")
        return 1
    except MemoryError:
        _say("hubbeam: computation failed: out of memory; try a coarser model (beam.elements), a larger "
             "analysis.output_dt or a shorter analysis.t_end")
        return 1
    except Exception as exc:  # the last line of defence: never a traceback for users
        if os.environ.get("HUBBEAM_DEBUG"):
            raise
        _say(f"hubbeam: internal error: {exc.__class__.__name__}: {exc} (set HUBBEAM_DEBUG=1 for a traceback)")
        return 1


if __name__ == "__main__":
    sys.exit(main())
