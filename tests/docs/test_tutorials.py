"""Every tutorial runs as written.

Each page of docs/tutorials/ is run top to bottom in a fresh directory:

- a fenced block with a ``title="NAME"`` (a TOML scenario, a CSV table) is written to NAME,
  as the reader is asked to save it;
- each line of a ``bash`` block is a ``hubbeam ...`` command, run in this process (numba's
  compiled code is loaded once), with ``> FILE`` taken as the reader's shell would; it must
  end with status 0 (``pip install`` lines are skipped; any other command is refused, so that
  a page cannot hold a line this test does not run);
- ``python`` blocks run in one namespace per page, in order, as a reader pasting them into one
  session would.

``text`` blocks show output and are not run. The tutorials keep their runs short, so the
pages run as they are written (no end time is shortened here).
"""

from __future__ import annotations

import contextlib
import io
import re
import shlex
from pathlib import Path

import pytest

TUTORIALS = Path(__file__).resolve().parents[2] / "docs" / "tutorials"
_FENCE = re.compile(r"^```(\w*)([^\n]*)\n(.*?)^```\s*$", re.S | re.M)
#: pages whose runs take more than a few seconds (once numba's cache is warm): a Python torque
#: law, an identification's many simulations; or whose models no other default test compiles
#: (the closed loop's controller on the bus: about 4 minutes of compiling on a cold cache)
SLOW = {"identification.md", "controlled_slew.md", "closed_loop.md"}


def blocks(page: Path) -> list[tuple[str, str | None, str]]:
    """(language, title or None, body) of the page's fenced code blocks, in order."""
    out = []
    for m in _FENCE.finditer(page.read_text(encoding="utf-8")):
        title = re.search(r'title="([^"]+)"', m.group(2))
        out.append((m.group(1), title.group(1) if title else None, m.group(3)))
    return out


def run_hubbeam(line: str) -> tuple[int, str, str]:
    """One shell line ``hubbeam ARGS [> FILE]`` run in this process: (status, stdout, stderr)."""
    from hubbeam.cli import main

    words = shlex.split(line, comments=True)
    target = None
    if ">" in words:
        k = words.index(">")
        assert len(words) == k + 2, f"only '> FILE' at the end of a line is understood: {line}"
        words, target = words[:k], words[k + 1]
    assert words[0] == "hubbeam", line
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(words[1:])
        except SystemExit as exc:  # argparse
            code = exc.code
    if target is not None:
        Path(target).write_text(out.getvalue(), encoding="utf-8")
    return code, out.getvalue(), err.getvalue()


def run_page(page: Path) -> None:
    namespace: dict = {"__name__": "__tutorial__"}
    for language, title, body in blocks(page):
        if title is not None:
            Path(title).write_text(body, encoding="utf-8")
        elif language == "bash":
            for line in body.splitlines():
                command = line.split("#", 1)[0].strip()
                if not command or command.startswith("pip install"):
                    continue
                assert command.startswith("hubbeam "), f"{page.name}: a shell line this test cannot run: {line}"
                code, _, err = run_hubbeam(command)
                assert code == 0, f"{page.name}: {command} -> exit {code}: {err}"
        elif language == "python":
            exec(compile(body, f"{page.name}:python", "exec"), namespace)  # noqa: S102 - the page's own code
        else:
            assert language in ("text", "toml", "csv"), f"{page.name}: a {language!r} block without a title"


def _pages():
    return [pytest.param(p, id=p.name, marks=[pytest.mark.slow] if p.name in SLOW else [])
            for p in sorted(TUTORIALS.glob("*.md"))]


def test_there_are_tutorials():
    assert {p.name for p in TUTORIALS.glob("*.md")} >= {"first_model.md", "several_beams.md", "controlled_slew.md",
                                                        "identification.md"}


def test_the_block_reader_sees_titles_languages_and_bodies(tmp_path):
    page = tmp_path / "page.md"
    page.write_text('Text\n\n```toml title="a.toml"\nx = 1\n```\n\n```bash\nhubbeam example exp1 > e.toml\n```\n'
                    '\n```python\nprint(1)\n```\n', encoding="utf-8")
    assert blocks(page) == [("toml", "a.toml", "x = 1\n"), ("bash", None, "hubbeam example exp1 > e.toml\n"),
                            ("python", None, "print(1)\n")]


@pytest.mark.parametrize("page", _pages())
def test_the_tutorial_runs_as_written(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    run_page(page)
