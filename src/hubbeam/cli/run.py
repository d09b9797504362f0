"""``hubbeam run``: the time integration and its result files, complete or partial."""

from __future__ import annotations


from hubbeam.cli.analysis import cmd_modes, cmd_static
from hubbeam.cli.common import check_targets, listed, progress_bar, say

def cmd_run(args, scenario) -> dict:
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
        return cmd_static(args, scenario) if kind == "static" else cmd_modes(args, scenario)
    from hubbeam import api, limits
    from hubbeam.interrupt import Interrupted

    targets = check_targets([Target("-o", args.output), Target("--csv", args.csv), Target("--plot", args.plot, "figure")],
                     args)
    if args.state and args.output is None:
        raise ScenarioError("--state: the state is stored in the NetCDF file; give -o OUT.nc")
    if args.plot is not None and not scenario.sensors:
        raise ScenarioError(f"--plot {args.plot}: the scenario has no sensors, so there is nothing to draw")
    plot_vars = plot_variables(args.plot_vars, args.plot, scenario)
    try:
        size = limits.check_run(scenario, state=args.state)
    except ScenarioError as exc:
        if not args.state:
            raise
        limits.check_run(scenario)  # too large without the state too: that error as it is
        raise ScenarioError(f"--state: {exc} (the recorded state adds {limits.state_values(scenario)} numbers per "
                            "output time; fewer beam elements need fewer)") from None
    if size.note:
        say(f"hubbeam: note: {size.note}")
    for line in api.reduction_warnings(scenario):
        say(f"hubbeam: warning: {line}")
    progress, finish = progress_bar(scenario.analysis.t_end)
    try:
        traj, failure = api.run(scenario, progress, state=args.state)
    except Interrupted as exc:
        traj, failure = exc.partial, exc
    finally:
        finish()
    for event in getattr(traj, "latches", None) or []:
        angle = event.to_dict()["angle_deg"]
        say(f"hubbeam: latch: beam {event.beam!r} locked at t = {event.time:.6g} s (angle {angle:.4g} deg): impulse "
            f"{event.impulse:+.4g} N m s, {event.energy:.4g} J dissipated")
    finish_run(targets, scenario, traj, failure, plot_vars, args.overrides)
    final = {name: values[-1] for name, values in traj.records.items()}
    summary = {"steps": traj.steps, "newton_iterations": traj.newton_iterations,
               "newton_iterations_per_step": traj.newton_iterations / max(traj.steps, 1),
               "lu_factorisations": traj.factorisations,
               "wall_time_s": traj.wall_time_s, "chart_switches": traj.chart_switches, "final": final}
    if any(b.joint is not None and b.joint.latch is not None for b in scenario.beam_tables):
        summary["latches"] = [event.to_dict() for event in traj.latches]
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


def plot_variables(text, plot, scenario) -> list[str] | None:
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


def finish_run(targets, scenario, traj, failure, plot_vars=None, overrides=()) -> None:
    """Write a run's results (complete or partial) and raise its failure with one line that
    says how far it got and what was written; the figure's title names the scenario and its
    ``overrides`` (--set), and what it leaves out is said on stderr."""
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
        from hubbeam.io.results import time_series

        chosen, note = plot_vars, "partial" if status else ""
        if chosen is None and not plots.timeseries_panels(dataset(), None):  # all zero: that is the result to draw
            chosen, note = time_series(dataset()), ", ".join(filter(None, [note, "every variable is zero throughout"]))
        title, subtitle = plots.run_title(scenario.name, overrides, note)
        left_out = plots.plot_timeseries(dataset(), path, title=title, variables=chosen, subtitle=subtitle)
        for why in dict.fromkeys(left_out.values()):
            say(f"hubbeam: note: --plot: not drawn ({why}; --plot-vars chooses): "
                + ", ".join(n for n, w in left_out.items() if w == why))

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
            what = (f"; the results so far are in {listed(written)} (marked partial)" if written
                    else "; no output file was requested, nothing written" if not targets else "")
            failure.detail = where + what + not_written
        raise failure
    if failure is not None:
        text = str(failure)
        if has_data and " at t = " not in text:
            text = f"time integration after t = {t_reached:g} s: {text}"
        if written:
            text += f" Results up to t = {t_reached:g} s are in {listed(written)} (marked partial)."
        raise ComputationError(text + not_written, partial=traj) from failure
    if errors:
        raise OutputError("; ".join(errors) + (f" (written: {listed(written)})" if written else ""))
    interrupt.raise_pending()


