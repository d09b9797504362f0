"""The README's command block ("What you can do now") and the Python block after it run as
written, in an empty directory: every file a line reads, an earlier line makes."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.docs.test_tutorials import run_hubbeam

README = Path(__file__).resolve().parents[2] / "README.md"


def section_blocks(title: str) -> list[tuple[str, str]]:
    """(language, body) of the fenced blocks of the README's section ``title``."""
    text = README.read_text(encoding="utf-8")
    section = text.split(f"## {title}\n", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"^```(\w+)\n(.*?)^```$", section, re.S | re.M)


def test_the_section_has_its_two_blocks():
    assert [language for language, _ in section_blocks("What you can do now")] == ["bash", "python"]


@pytest.mark.slow
def test_what_you_can_do_now_runs_as_written_in_an_empty_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    (bash, commands), (python, code) = section_blocks("What you can do now")
    for line in commands.splitlines():
        for command in line.split("#", 1)[0].split("&&"):
            command = command.strip()
            assert command.startswith("hubbeam "), f"a README line this test cannot run: {line}"
            status, _, err = run_hubbeam(command)
            assert status == 0, f"{command} -> exit {status}: {err}"
    for made in ("exp1.png", "rotor3.gif", "rotor3_vtk/rotor3.pvd", "ss.nc", "report", "campbell.png", "sweep.nc",
                 "app", "fit.png"):
        assert (tmp_path / made).exists(), made
    exec(compile(code, "README.md:python", "exec"), {"__name__": "__readme__"})  # noqa: S102 - the README's own code
