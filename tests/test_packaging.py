"""The dependencies pyproject.toml declares match what the package imports: every third-party
module imported under src/ is declared (at module level: a core dependency; inside a function,
which is how optional features import: a core dependency or one of an extra), and every core
dependency is imported somewhere (or is listed below with the reason it is needed anyway)."""

import ast
import re
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCES = ROOT / "src" / "hubbeam"

#: import name -> distribution name, where they differ
DISTRIBUTION = {"yaml": "pyyaml", "PIL": "pillow", "sklearn": "scikit-learn", "imageio_ffmpeg": "imageio-ffmpeg",
                "mpl_toolkits": "matplotlib"}  # mpl_toolkits.mplot3d ships with matplotlib
#: core dependencies that no module imports, and why they are declared
NOT_IMPORTED = {"h5py": "the HDF5 library h5netcdf writes NetCDF with"}


def _normal(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _requirement_name(requirement: str) -> str:
    return _normal(re.match(r"[A-Za-z0-9_.-]+", requirement.strip()).group(0))


def declared() -> tuple[set[str], set[str]]:
    """(core distributions, distributions of any extra), normalised names."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    core = {_requirement_name(r) for r in project.get("dependencies", [])}
    extras = {_requirement_name(r) for group in project.get("optional-dependencies", {}).values() for r in group}
    return core, extras


def _imported_names(node) -> list[str]:
    if isinstance(node, ast.Import):
        return [a.name.split(".")[0] for a in node.names]
    if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
        return [node.module.split(".")[0]]
    return []


def third_party_imports(path: Path) -> dict[str, bool]:
    """{top-level module: imported at module level (not only inside a function)} of one file."""
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    inside = set()
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in ast.walk(fn):
                inside.add(id(node))
    found: dict[str, bool] = {}
    for node in ast.walk(tree):
        for name in _imported_names(node):
            if name in sys.stdlib_module_names or name == "hubbeam" or name == "__future__":
                continue
            found[name] = found.get(name, False) or id(node) not in inside
    return found


def all_imports() -> dict[str, tuple[bool, list[str]]]:
    out: dict[str, tuple[bool, list[str]]] = {}
    for path in sorted(SOURCES.rglob("*.py")):
        for name, top in third_party_imports(path).items():
            was_top, files = out.get(name, (False, []))
            out[name] = (was_top or top, files + [str(path.relative_to(ROOT))])
    return out


def _distribution(module: str) -> str:
    return _normal(DISTRIBUTION.get(module, module))


def test_every_imported_module_is_declared():
    core, extras = declared()
    missing = []
    for module, (top_level, files) in all_imports().items():
        dist = _distribution(module)
        if dist in core:
            continue
        if top_level:
            missing.append(f"{module} (imported at module level in {files[0]}: a core dependency)")
        elif dist not in extras:
            missing.append(f"{module} (imported in {files[0]}: declare it, in an extra if optional)")
    assert not missing, "undeclared: " + "; ".join(missing)


def test_every_core_dependency_is_imported():
    core, _ = declared()
    imported = {_distribution(m) for m in all_imports()}
    unused = sorted(d for d in core if d not in imported and d not in NOT_IMPORTED)
    assert not unused, f"declared but never imported: {unused}"


def test_the_checks_see_what_they_should(tmp_path):
    """The import scan itself: module-level and function-level imports, relative and standard
    library ones left out."""
    f = tmp_path / "m.py"
    f.write_text("import os\nimport numpy as np\nfrom scipy.linalg import eig\nfrom . import x\n"
                 "def g():\n    import pandas\n    from imageio_ffmpeg import get_ffmpeg_exe\n")
    assert third_party_imports(f) == {"numpy": True, "scipy": True, "pandas": False, "imageio_ffmpeg": False}
    assert _distribution("imageio_ffmpeg") == "imageio-ffmpeg"
    assert _requirement_name("dask[distributed]>=2024.1") == "dask"
