"""``hubbeam campbell``, ``sweep``, ``identify``, ``applicability`` and ``reproduce``."""

from __future__ import annotations

import json
import math
import os

from hubbeam.cli.common import MAX_MEASURED_BYTES, check_targets, limit_workers, listed, load, progress_bar, say, write_jobs

def cmd_campbell(args, scenario) -> dict:
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
    targets = check_targets([Target("-o", args.output, "figure"), Target("--data", args.data)], args)
    from hubbeam.studies.campbell import campbell

    progress, finish = progress_bar(len(forms) * speeds.size, label="campbell", unit="points")
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

    write_jobs([(t, figure if t.option == "-o" else data) for t in targets])
    import numpy as np

    short = {f: int(np.isfinite(ds["tracked_frequency_hz"].sel(formulation=f).values).any(axis=0).sum()) for f in forms}
    short = {f: n for f, n in short.items() if n < args.count}
    if short:
        say(f"hubbeam: note: --count {args.count}, but the model has only "
             f"{', '.join(f'{n} modes with {f}' for f, n in short.items())} (the others are null; more beam.elements "
             "give more)")
    if frange is not None and targets and targets[0].option == "-o":
        f = ds["frequency_hz"].values
        f = f[np.isfinite(f)]
        if f.size and not ((f >= frange[0]) & (f <= frange[1])).any():
            say(f"hubbeam: note: {'--fmax' if args.fmax is not None else '--frange'}: no frequency lies in "
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


def cmd_sweep(args, scenario) -> dict:
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
    limit_workers(args.workers, "--workers")
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
    targets = check_targets([Target("-o", args.output), Target("--plot", args.plot, "figure")], args)
    progress, finish = progress_bar(total, label="sweep", unit="points")
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
        title, subtitle = plots.run_title(f"{scenario.name}: sweep over {', '.join(varied)}", args.overrides)
        plots.plot_sweep(ds, path, title=title, subtitle=subtitle)

    jobs = [(t, data if t.option == "-o" else figure) for t in targets]
    if partial is not None:
        from hubbeam import interrupt
        from hubbeam.io.targets import write_all

        written, errors = write_all(jobs)
        interrupt.take_pending()
        done = ds.attrs.get("points_done", 0)
        partial.detail = (f" after {done} of {total} points; " +
                          (f"the results so far are in {listed(written)} (marked partial; the points not run "
                           "are marked failed)" if written else "nothing written") +
                          (f"; could not write: {'; '.join(errors)}" if errors else ""))
        raise partial
    write_jobs(jobs)
    failed = int(ds["failed"].sum())
    if not args.json:
        print(f"{total} points ({failed} failed) -> {args.output}")
    return {"points": total, "failed": failed, "output": args.output, "dims": dict(ds.sizes)}


def read_measured(path: str, signal: str):
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


def cmd_identify(args, scenario) -> dict:
    import numpy as np

    from hubbeam.io.targets import Target
    from hubbeam.studies.identify import identify

    targets = check_targets([Target("-o", args.output, "figure")], args, ("measured file", args.measured))
    times, measured = read_measured(args.measured, args.signal)
    progress, _ = progress_bar(None, label="identify", unit="simulations")
    fit = identify(scenario, times, measured, args.fit, signal=args.signal, progress=progress)
    d = fit.to_dict()
    if targets:
        from hubbeam import plots

        title, subtitle = plots.run_title(f"{scenario.name}: fit of {', '.join(args.fit)}", args.overrides)
        kind = next((s.kind for s in scenario.sensors if args.signal in s.columns), None)
        write_jobs([(targets[0], lambda p: plots.plot_fit(fit.times, fit.measured, fit.fitted, p, args.signal,
                                                          title=title, kind=kind, subtitle=subtitle))])
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


def cmd_applicability(args) -> dict:
    import time
    from pathlib import Path

    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.targets import Target
    from hubbeam.studies.applicability import applicability_map
    from hubbeam.studies.variants import parse_range

    scenario = load(args)
    thickness, ratio = parse_range(args.thickness, "--thickness"), parse_range(args.ratio, "--ratio")
    if (thickness <= 0).any() or (ratio < 0).any() or (ratio >= 1).any():
        raise ScenarioError("--thickness must be > 0 and --ratio in [0, 1)")
    limit_workers(args.workers, "--workers")
    check_targets([Target("-o", args.output, "directory")], args)
    from hubbeam.io.targets import check_inside

    check_inside("-o", args.output, [f"applicability.{ext}" for ext in ("png", "nc", "md")])
    total = thickness.size * (ratio.size + 1)
    progress, finish = progress_bar(total, label="applicability", unit="tasks")
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

        title, subtitle = plots.run_title(f"FFR against ANCF: {scenario.name}", args.overrides)
        plots.plot_applicability(ds, path, title=title, subtitle=subtitle)

    def table(path):
        Path(path).write_text(text, encoding="utf-8")

    write_jobs([(Target("-o", str(out / "applicability.nc")), data), (Target("-o", str(out / "applicability.png")), figure),
            (Target("-o", str(out / "applicability.md")), table)])
    failed = int((ds["message"] != "").sum())
    if not args.json:
        print(f"{total} tasks ({failed} failed) in {wall:.0f} s -> {out}/applicability.png, .nc, .md")
    return {"tasks": total, "failed": failed, "wall_time_s": wall, "output": str(out)}


def cmd_reproduce(args) -> int:
    import shutil
    import tempfile
    from pathlib import Path

    from hubbeam.io.targets import OutputError, Target
    from hubbeam.reproduce.pipeline import reproduce

    limit_workers(args.jobs, "--jobs")
    check_targets([Target("-o", args.output, "directory")], args)
    from hubbeam.io.targets import check_inside

    check_inside("-o", args.output, ["report.md", "tables.json"])

    def progress(done, total, outcome):
        state = "failed" if outcome.failure else "done"
        say(f"hubbeam: note: reproduce {done} of {total} runs ({100 * done / total:.0f} %): {outcome.case.key} "
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


