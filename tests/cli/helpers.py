"""Running the command line in tests: in this process (fast: numba is loaded once) or as a
real subprocess (for signals and resource limits), and the contract every outcome must keep."""

from __future__ import annotations

import contextlib
import io
import json
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "src" / "hubbeam" / "examples"


def cli(*args) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of ``hubbeam ARGS`` run in this process."""
    from hubbeam.cli import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main([str(a) for a in args])
        except SystemExit as exc:  # argparse
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def hubbeam(*args, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "hubbeam.cli", *map(str, args)], capture_output=True, text=True,
                          timeout=kwargs.pop("timeout", 600), **kwargs)


def _default_signals():
    # a test run started in the background of a shell ignores SIGINT, and so would the child:
    # hubbeam keeps a signal ignored that was ignored when it started (as nohup expects)
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def popen(*args, **kwargs) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "hubbeam.cli", *map(str, args)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_default_signals, **kwargs)


def finish(proc: subprocess.Popen, timeout: float = 120) -> tuple[str, str]:
    """stdout and stderr of a process that should end by itself; killed if it does not."""
    try:
        return proc.communicate(timeout=timeout)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()


def assert_contract(code, stdout: str, stderr: str, json_out: bool = False) -> None:
    """What every command keeps (interface.md): an exit status of 0, 1, 2 or 128 + N; on
    failure one line on stderr and no traceback or internal
    error; with --json and success, one JSON object without NaN on stdout."""
    assert code in (0, 1, 2, 129, 130, 143), (code, stderr)
    assert "Traceback" not in stderr and "internal error" not in stderr, stderr
    lines = [ln for ln in stderr.splitlines() if ln.strip() and not ln.startswith("hubbeam: note:")]
    if code != 0:
        assert len(lines) == 1, stderr
        assert lines[0].startswith("hubbeam"), stderr
    if json_out and code == 0:
        json.loads(stdout, parse_constant=lambda c: (_ for _ in ()).throw(AssertionError(f"{c} in JSON")))


def without_notes(stderr: str) -> str:
    """stderr without its notes (``hubbeam: note:`` lines, such as the one before the first
    compile on a cold numba cache, which a test cannot count on): the error or failure line."""
    return "\n".join(ln for ln in stderr.splitlines() if ln.strip() and not ln.startswith("hubbeam: note:"))


def no_temporary_files(directory) -> bool:
    """No half-written results left behind (the atomic writes' temporary files)."""
    return not [p for p in Path(directory).iterdir() if ".part" in p.name or p.name.startswith(".hubbeam-probe")]
