"""What every command shares: one-line messages, loading the scenario, checking and writing the
output targets, JSON on stdout, progress lines and the first-compile note. Only the standard
library at module level (see :mod:`hubbeam.cli`)."""

from __future__ import annotations

import json
import math
import os
import sys

#: a measured file may be larger than a scenario file
MAX_MEASURED_BYTES = 256 * 2**20


# ------------------------------------------------------------------------------ helpers
def say(text: str) -> None:
    """One line on stderr (a closed terminal, after SIGHUP, is not an error)."""
    try:
        print(" ".join(str(text).split()), file=sys.stderr, flush=True)
    except (OSError, ValueError):
        pass


class _GuardedStream:
    """A text stream whose failed writes (a full disk, an I/O error) raise OutputError naming
    ``name``; a reader that went away (BrokenPipeError) stays what it is."""

    def __init__(self, stream, name: str):
        self._stream, self._name = stream, name

    def _guard(self, method, *args):
        try:
            return method(*args)
        except BrokenPipeError:
            raise
        except OSError as exc:
            from hubbeam.io.targets import OutputError

            raise OutputError(f"{self._name}: cannot write ({exc.strerror or exc.__class__.__name__})") from None

    def write(self, text):
        return self._guard(self._stream.write, text)

    def flush(self):
        return self._guard(self._stream.flush)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def guarded_stdout(stream):
    """``stream`` (sys.stdout) with its failed writes reported as failed writes of "stdout"."""
    return _GuardedStream(stream, "stdout")


def load(args):
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
        say(f"hubbeam: note: {line}")
    args.tables = [(f"table of {key}", path) for _, key, path in table_files(scenario)]
    args.tables += [(f"matrices of controllers[{i}].file", c.file) for i, c in enumerate(scenario.controllers)]
    return scenario


def check_targets(targets, args, *inputs):
    """Check the output targets before computing (ScenarioError naming the option); the
    scenario file and the CSV tables it reads are inputs that no target may overwrite."""
    from hubbeam.io.targets import check_outputs

    files = [("scenario file", getattr(args, "scenario", None))] + getattr(args, "tables", []) + list(inputs)
    return check_outputs(targets, files)


def listed(paths) -> str:
    return ", ".join(str(p) for p in paths)


def write_jobs(jobs, interruptible: bool = False) -> list[str]:
    """Write (target, writer) jobs; OutputError (exit 1) naming the ones that failed and the
    ones written; a signal during the writes takes effect after them (``interruptible``: at
    once, for writers that are the computation itself, see io.targets.write_all)."""
    from hubbeam import interrupt
    from hubbeam.io.targets import OutputError, write_all

    written, errors = write_all(jobs, interruptible)
    if errors:
        also = f" (written: {listed(written)})" if written else ""
        raise OutputError("; ".join(errors) + also)
    interrupt.raise_pending()
    return written


def limit_workers(value, option: str) -> None:
    from hubbeam.io.scenario import ScenarioError

    if value is None:
        return
    cores = os.cpu_count() or 1
    if value < 1:
        raise ScenarioError(f"{option}: must be >= 1 (got {value})")
    if value > 4 * cores:
        raise ScenarioError(f"{option}: {value} processes on {cores} cores; at most {4 * cores}")


def json_safe(obj, path: str = "", bad: list | None = None):
    """``obj`` with every non-finite float replaced by None (JSON has no NaN); their paths
    are appended to ``bad``."""
    import numpy as np

    if isinstance(obj, dict):
        return {k: json_safe(v, f"{path}.{k}" if path else str(k), bad) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v, f"{path}[{i}]", bad) for i, v in enumerate(obj)]
    if isinstance(obj, np.ndarray):
        return json_safe(obj.tolist(), path, bad)
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


def print_json(result: dict) -> None:
    bad: list[str] = []
    safe = json_safe(result, "", bad)
    if bad:
        safe["non_finite"] = {"paths": bad, "reason": "these values are not finite numbers (NaN or infinity); "
                                                      "JSON has none, so they are null"}
    print(json.dumps(safe, allow_nan=False))


def numerical_failure(what: str, exc: BaseException):
    """A ComputationError for a linear-algebra failure (a matrix with NaN, not positive
    definite) inside ``what``."""
    from hubbeam.errors import ComputationError

    reason = (str(exc).splitlines() or [""])[0][:160]
    return ComputationError(f"{what} failed ({exc.__class__.__name__}: {reason}); try more analysis.load_steps or "
                            "beam.elements, and check the scenario's values and units (SI)")


#: seconds between two progress lines when stderr is not a terminal (none before the first interval)
PROGRESS_EVERY = 10.0


def compile_note() -> None:
    """One line before numba compiles the solver into its on-disk cache (the first run on a machine)."""
    from hubbeam.solvers.compiled_alpha import cache_is_cold

    if cache_is_cold():
        say("hubbeam: note: compiling the solver for this machine (first run only, about a minute)")


def progress_bar(t_end: float | None, label: str = "run", unit: str = "s"):
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
                say(f"hubbeam: note: {label}: {done:g} {unit} so far")
            else:
                where = f"t = {done:.4g} of {t_end:g} s" if unit == "s" else f"{done:g} of {t_end:g} {unit}"
                say(f"hubbeam: note: {label} {where} ({100 * done / max(t_end, 1e-300):.0f} %)")

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


def raised_in(exc: BaseException) -> str:
    """The function (and module) where an exception was raised."""
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None:
        return "an unknown place"
    code = tb.tb_frame.f_code
    module = tb.tb_frame.f_globals.get("__name__", "?")
    return f"{module}.{code.co_name}"


