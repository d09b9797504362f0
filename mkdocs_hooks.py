"""mkdocs hook: README.md is the site's start page (index.md).

README.md links to the documentation pages as ``docs/PAGE.md`` and to figures as
``docs/figures/NAME.png``, so that it reads correctly on GitHub; served as ``index.md`` inside
``docs/`` those links lose their ``docs/`` prefix. Any other relative link in README.md (to a
file outside ``docs/``, which the site does not have) is an error, so ``mkdocs build
--strict`` fails rather than publish a broken link.
"""

from __future__ import annotations

import re
from pathlib import Path

from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

README = Path(__file__).resolve().parent / "README.md"
#: a markdown link or image target: ](target) or ](target "title")
_TARGET = re.compile(r"\]\(([^)\s]+)(\s+\"[^\"]*\")?\)")


def readme_as_index(text: str) -> str:
    """README.md's text with its links made relative to ``docs/`` (ValueError for a relative
    link that leaves ``docs/``)."""

    def fix(match: re.Match) -> str:
        target, title = match.group(1), match.group(2) or ""
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            return match.group(0)  # an absolute URL or an anchor of the page itself
        if not target.startswith("docs/"):
            raise ValueError(f"README.md links to {target!r}, outside docs/: the site cannot serve it")
        return f"]({target.removeprefix('docs/')}{title})"

    return _TARGET.sub(fix, text)


def on_files(files, config):
    if files.get_file_from_path("index.md") is not None:
        raise PluginError("docs/index.md exists: the start page is README.md (served as index.md by mkdocs_hooks.py)")
    try:
        content = readme_as_index(README.read_text(encoding="utf-8"))
    except ValueError as exc:
        raise PluginError(str(exc)) from None
    files.append(File.generated(config, "index.md", content=content))
    return files
