"""The ``hubbeam`` command line (see ../shared/interface.md).

Exit status: 0 success, 2 bad input (one line naming the key), 1 failed computation
(a message saying where and what to try). No traceback reaches the user unless the
environment variable HUBBEAM_DEBUG is set.
"""

from __future__ import annotations

import argparse
import json
import os
import sys

import numpy as np

from hubbeam.io.scenario import EXAMPLES, ScenarioError, example_text, load_scenario
from hubbeam.errors import ComputationError


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse prints usage and exits 2: keep it to two lines
        self.print_usage(sys.stderr)
        print(f"hubbeam: error: {message}", file=sys.stderr)
        raise SystemExit(2)


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="hubbeam", description="Rotating hub with a 3D flexible beam: ANCF with torsion and FFR, side by side.")
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
    run.add_argument("--plot", help="PNG figure")
    st = scenario_cmd("static", "static equilibrium under gravity and loads (hub held at theta = 0)")
    st.add_argument("--plot", help="PNG figure of the deformed beam")
    scenario_cmd("modes", "natural frequencies about the static equilibrium (steady rotation for a constant drive)")
    camp = scenario_cmd("campbell", "natural frequencies about the steadily rotating state against hub speed")
    camp.add_argument("--omega", required=True, metavar="START:STOP:N", help="hub speeds (rad/s)")
    camp.add_argument("--count", type=int, default=6, help="modes per speed (default 6)")
    camp.add_argument("-o", "--output", help="PNG figure")
    camp.add_argument("--data", help="NetCDF file of the frequencies")
    camp.add_argument("--formulations", default="ancf,ffr,ffr+", help="comma-separated: ancf, ffr, ffr+ (default all)")
    sw = scenario_cmd("sweep", "run the scenario over the cartesian product of varied keys, on Dask")
    sw.add_argument("--vary", action="append", required=True, metavar="KEY=START:STOP:N",
                    help="a varied key and its values (numpy.linspace); repeat for more keys")
    sw.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    sw.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: all cores)")
    sw.add_argument("-o", "--output", required=True, help="NetCDF file of the merged results")
    sw.add_argument("--plot", help="PNG figure of the results (up to four variables)")
    idf = scenario_cmd("identify", "fit scenario parameters to a measured time series (least squares)")
    idf.add_argument("measured", help="CSV with a header row: a 'time' column (s) and the signal's column")
    idf.add_argument("--fit", nargs="+", required=True, metavar="KEY", help="scenario keys to fit (e.g. damping.linear)")
    idf.add_argument("--signal", default="strain_P1", help="the sensor (column) to match (default strain_P1)")
    idf.add_argument("-o", "--output", help="PNG figure of fit and data")
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
    ex = sub.add_parser("example", help="print a bundled scenario")
    ex.add_argument("name", help=f"one of: {', '.join(EXAMPLES)}")
    return p


def _print_static(d: dict) -> None:
    t = d["tip_displacement"]
    print(f"tip displacement (hub frame): radial {t['radial']:+.6g} m, vertical {t['vertical']:+.6g} m, "
          f"tangential {t['tangential']:+.6g} m")
    print(f"tip position: [{', '.join(f'{v:.6g}' for v in d['tip_position'])}] m")
    print(f"Newton iterations {d['newton_iterations']} over {d['load_steps']} load steps, "
          f"{d['chart_switches']} chart replacements")


def _cmd_static(args, scenario) -> dict:
    from hubbeam import api

    result = api.static(scenario)
    d = result.to_dict()
    if getattr(args, "plot", None):
        from hubbeam import plots

        x0, F0 = result.system.initial_state(0.0)
        sol = result.solution
        plots.plot_deformed(result.system, x0, F0, sol.x, sol.chart, args.plot, title=f"{scenario.name}: static equilibrium")
    if not args.json:
        _print_static(d)
    return d


def _cmd_modes(args, scenario) -> dict:
    from hubbeam import api

    d = api.modes(scenario).to_dict()
    if not args.json:
        print(f"natural frequencies (Hz) about the {d['about']}, {d['rigid_modes']} rigid mode(s) left out:")
        for i, f in enumerate(d["frequencies_hz"], 1):
            print(f"  {i:3d}  {f:12.6f}")
    return d


def _cmd_run(args, scenario) -> dict:
    kind = scenario.analysis.kind
    if kind == "static":
        return _cmd_static(args, scenario)
    if kind == "modes":
        return _cmd_modes(args, scenario)
    from hubbeam import api
    from hubbeam.io import results

    progress, finish = _progress_bar(scenario.analysis.t_end)
    try:
        traj, failure = api.run(scenario, progress)
    finally:
        finish()
    if traj is not None and traj.times:
        if args.output:
            results.write_trajectory_netcdf(traj, scenario, args.output)
        if args.csv or args.plot:
            ds = results.to_dataset(traj, scenario)
            if args.csv:
                results.write_csv(ds, args.csv)
            if args.plot:
                from hubbeam import plots

                plots.plot_timeseries(ds, args.plot, title=scenario.name)
    if failure is not None:
        raise failure
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


def _cmd_campbell(args, scenario) -> dict:
    from hubbeam.studies.campbell import campbell
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
    progress, finish = _progress_bar(len(forms) * speeds.size, label="campbell", unit="points")
    try:
        ds = campbell(scenario, speeds, count=args.count, formulations=forms,
                      progress=(lambda done, total: progress(done)) if progress else None)
    finally:
        finish()
    if args.output:
        from hubbeam import plots

        plots.plot_campbell(ds, args.output, title=f"Campbell diagram: {scenario.name}")
    if args.data:
        from hubbeam.io.results import write_netcdf

        write_netcdf(ds, args.data)
    result = {"omega": speeds.tolist(),
              "frequencies_hz": {str(f): ds["frequency_hz"].sel(formulation=f).values.tolist() for f in forms}}
    if not args.json:
        for f in forms:
            first = ds["frequency_hz"].sel(formulation=f).values[:, 0]
            print(f"{f:5s} first mode: {first[0]:.4f} Hz at {speeds[0]:g} rad/s -> {first[-1]:.4f} Hz at {speeds[-1]:g} rad/s")
    return result


def _cmd_sweep(args, scenario) -> dict:
    from hubbeam.io.results import write_netcdf
    from hubbeam.studies.sweep import format_value, sweep
    from hubbeam.studies.variants import parse_vary

    varied = {}
    for text in args.vary:
        key, values, integral = parse_vary(text)
        varied[key] = (values, integral)
    if args.workers is not None and args.workers < 1:
        raise ScenarioError(f"--workers: must be >= 1 (got {args.workers})")
    # check the first point here, so that a bad key is a clear error and not a sweep of failures
    first = [f"{k}={format_value(v[0][0], v[1])}" for k, v in varied.items()]
    from hubbeam.io.scenario import apply_overrides, validate

    validate(apply_overrides(scenario.to_dict(), first))
    total = int(np.prod([len(v[0]) for v in varied.values()]))
    progress, finish = _progress_bar(total, label="sweep", unit="points")
    try:
        ds = sweep(scenario, varied, scheduler=args.scheduler, workers=args.workers,
                   progress=(lambda done, n: progress(done)) if progress else None)
    finally:
        finish()
    ds.attrs["scenario_toml"] = json.dumps(scenario.to_dict())
    write_netcdf(ds, args.output)
    if args.plot:
        from hubbeam import plots

        plots.plot_sweep(ds, args.plot, title=f"sweep of {scenario.name} over {', '.join(varied)}")
    failed = int(ds["failed"].sum())
    if not args.json:
        print(f"{total} points ({failed} failed) -> {args.output}")
    return {"points": total, "failed": failed, "output": args.output, "dims": dict(ds.sizes)}


def _read_measured(path: str, signal: str):
    import pandas as pd

    try:
        table = pd.read_csv(path)
    except FileNotFoundError:
        raise ScenarioError(f"{path}: no such file") from None
    except Exception as exc:
        raise ScenarioError(f"{path}: cannot read as CSV ({exc.__class__.__name__})") from None
    for column in ("time", signal):
        if column not in table.columns:
            raise ScenarioError(f"{path}: no column {column!r} (columns: {', '.join(map(str, table.columns))})")
    data = table[["time", signal]].apply(pd.to_numeric, errors="coerce").dropna()
    return data["time"].to_numpy(float), data[signal].to_numpy(float)


def _cmd_identify(args, scenario) -> dict:
    from hubbeam.studies.identify import identify

    times, measured = _read_measured(args.measured, args.signal)
    fit = identify(scenario, times, measured, args.fit, signal=args.signal)
    if args.output:
        from hubbeam import plots

        plots.plot_fit(fit.times, fit.measured, fit.fitted, args.output, args.signal,
                       title=f"{scenario.name}: fit of {', '.join(args.fit)}")
    d = fit.to_dict()
    if not args.json:
        for name, p in d["parameters"].items():
            print(f"{name} = {p['value']:.6g} +- {p['ci95']:.3g} (95 %), from {p['initial']:.6g}")
        if len(args.fit) > 1:
            print(f"correlation: {np.array2string(np.array(d['correlation']), precision=3)}")
        print(f"rms residual {d['rms_residual']:.3g}, {d['simulations']} simulations")
    return d


def _cmd_applicability(args) -> dict:
    import time
    from pathlib import Path

    from hubbeam import plots
    from hubbeam.io.results import write_netcdf
    from hubbeam.io.scenario import load_example
    from hubbeam.studies.applicability import applicability_map
    from hubbeam.studies.variants import parse_range

    scenario = load_scenario(args.scenario, args.overrides) if args.scenario else load_example("exp1", args.overrides)
    thickness, ratio = parse_range(args.thickness, "--thickness"), parse_range(args.ratio, "--ratio")
    if (thickness <= 0).any() or (ratio < 0).any() or (ratio >= 1).any():
        raise ScenarioError("--thickness must be > 0 and --ratio in [0, 1)")
    total = thickness.size * (ratio.size + 1)
    progress, finish = _progress_bar(total, label="applicability", unit="tasks")
    start = time.perf_counter()
    try:
        ds = applicability_map(scenario, thickness, ratio, scheduler=args.scheduler, workers=args.workers,
                               progress=(lambda done, n: progress(done)) if progress else None)
    finally:
        finish()
    wall = time.perf_counter() - start
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    write_netcdf(ds, out / "applicability.nc")
    plots.plot_applicability(ds, out / "applicability.png", title=f"FFR against ANCF: {scenario.name}")
    lines = ["| h (mm) | w_m/L | " + " | ".join(f"ω/ω1 = {r:.2f}" for r in ratio) + " |",
             "|---|---|" + "---|" * ratio.size]
    for i, h in enumerate(thickness):
        cells = [f"{ds['frequency_error_pct'].values[i, j]:+.1f} / {ds['deflection_error_pct'].values[i, j]:+.1f}"
                 for j in range(ratio.size)]
        lines.append(f"| {1000 * h:.2f} | {ds['w_m_over_L'].values[i]:.2f} | " + " | ".join(cells) + " |")
    (out / "applicability.md").write_text(
        f"# FFR's error against ANCF ({scenario.name})\n\nEach cell: first-frequency error / tip-deflection error "
        f"of FFR in percent. {total} tasks, {wall:.0f} s.\n\n" + "\n".join(lines) + "\n")
    failed = int((ds["message"] != "").sum())
    if not args.json:
        print(f"{total} tasks ({failed} failed) in {wall:.0f} s -> {out}/applicability.png, .nc, .md")
    return {"tasks": total, "failed": failed, "wall_time_s": wall, "output": str(out)}


def _cmd_reproduce(args) -> int:
    from hubbeam.reproduce.pipeline import reproduce

    if args.jobs is not None and args.jobs < 1:
        raise ScenarioError(f"--jobs: must be >= 1 (got {args.jobs})")

    def progress(done, total, outcome):
        state = "failed" if outcome.failure else "done"
        print(f"[{done}/{total}] {outcome.case.key}: {state} in {outcome.wall_time_s:.0f} s", file=sys.stderr)

    path, _ = reproduce(args.output, quick=args.quick, jobs=args.jobs, progress=progress)
    print(f"report: {path}")
    return 0


def _progress_bar(t_end: float, label: str = "simulating", unit: str = "s"):
    """A rich progress bar on a terminal, nothing otherwise: (update(t), finish())."""
    if not sys.stderr.isatty():
        return None, lambda: None
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

    done = "t = {task.completed:.2f} s" if unit == "s" else "{task.completed:.0f} / {task.total:.0f} " + unit
    bar = Progress(TextColumn(label), BarColumn(), TextColumn(done),
                   TimeRemainingColumn(), transient=True)
    task = bar.add_task("run", total=t_end)
    bar.start()
    return (lambda t: bar.update(task, completed=t)), bar.stop


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    try:
        if args.command == "example":
            sys.stdout.write(example_text(args.name))
            return 0
        if args.command == "reproduce":
            return _cmd_reproduce(args)
        if args.command == "applicability":
            result = _cmd_applicability(args)
            if args.json:
                print(json.dumps(result))
            return 0
        scenario = load_scenario(args.scenario, args.overrides)
        handler = {"static": _cmd_static, "modes": _cmd_modes, "run": _cmd_run, "campbell": _cmd_campbell,
                   "sweep": _cmd_sweep, "identify": _cmd_identify}[args.command]
        result = handler(args, scenario)
        if args.json:
            print(json.dumps(result))
        return 0
    except ScenarioError as exc:
        print(f"hubbeam: error: {exc}", file=sys.stderr)
        return 2
    except ComputationError as exc:
        print(f"hubbeam: computation failed: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("hubbeam: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader went away (`hubbeam run ... | head`): stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # so that Python's final flush does not fail again
        return 0
    except Exception as exc:  # the last line of defence: never a traceback for users
        if os.environ.get("HUBBEAM_DEBUG"):
            raise
        print(f"hubbeam: internal error: {exc.__class__.__name__}: {exc} (set HUBBEAM_DEBUG=1 for a traceback)",
              file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
