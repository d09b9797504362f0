"""The start page: README.md is served as the site's index.md by mkdocs_hooks.py."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: a markdown link or image target
TARGET = re.compile(r"\]\(([^)\s]+)")


def _hooks():
    pytest.importorskip("mkdocs")
    sys.path.insert(0, str(ROOT))
    try:
        import mkdocs_hooks
    finally:
        sys.path.remove(str(ROOT))
    return mkdocs_hooks


def test_every_relative_link_of_the_readme_is_a_file_under_docs():
    # what GitHub shows: the README's links resolve from the repository root
    for target in TARGET.findall((ROOT / "README.md").read_text(encoding="utf-8")):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            continue
        path = target.split("#", 1)[0]
        assert path.startswith("docs/"), f"README.md links outside docs/: {target}"
        assert (ROOT / path).is_file(), f"README.md links to a missing file: {target}"


def test_the_hook_makes_readme_links_relative_to_docs():
    hooks = _hooks()
    text = ("See [the reference](docs/scenario.md#analysis), ![a figure](docs/figures/x.png \"title\"), "
            "[elsewhere](https://example.org/docs/a.md) and [here](#top).")
    assert hooks.readme_as_index(text) == (
        "See [the reference](scenario.md#analysis), ![a figure](figures/x.png \"title\"), "
        "[elsewhere](https://example.org/docs/a.md) and [here](#top).")


def test_the_hook_refuses_a_link_the_site_cannot_serve():
    hooks = _hooks()
    with pytest.raises(ValueError, match="benchmarks/README.md"):
        hooks.readme_as_index("[cases](benchmarks/README.md)")


def test_there_is_no_second_start_page():
    assert not (ROOT / "docs" / "index.md").exists()  # the start page is README.md
