"""Start-up of the command line: what ``hubbeam --help`` and ``hubbeam example`` load, and
the garbage collector left alone when main() is called with arguments (issue 13)."""

from __future__ import annotations

import gc
import subprocess
import sys

from tests.cli.helpers import cli, hubbeam


def test_help_and_example_load_neither_pydantic_nor_numpy():
    code = ("import sys, contextlib, io\n"
            "from hubbeam.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    assert main(['example', 'exp1']) == 0\n"
            "    try:\n"
            "        main(['--help'])\n"
            "    except SystemExit:\n"
            "        pass\n"
            "print(sorted(m for m in ('pydantic', 'numpy', 'numba', 'scipy') if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_main_with_arguments_leaves_the_garbage_collector_alone():
    frozen = gc.get_freeze_count()
    code, out, _ = cli("example", "exp1")
    assert code == 0 and out.startswith("#")
    assert gc.isenabled() and gc.get_freeze_count() == frozen


def test_the_process_runs_and_exits_cleanly_with_the_collector_frozen():
    out = hubbeam("example", "cantilever")
    assert out.returncode == 0 and out.stderr == "" and "[beam]" in out.stdout
    bad = hubbeam("example", "nope")
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "example" in bad.stderr
