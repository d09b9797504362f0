"""The files a command reads and writes: checked before any computation, written atomically.

- :func:`check_input_file`: a scenario or measured file must be a regular file of at most
  :data:`MAX_INPUT_BYTES`, UTF-8 text without NUL characters (``/dev/zero``, a directory or a
  binary file is bad input, not a hang or an internal error).
- :func:`check_outputs`: every output target (``-o``, ``--csv``, ``--plot``, ``--data``, an
  output directory) is checked before the computation starts: its directory exists and can
  be written (probed by creating and removing a file there, which also catches read-only
  file systems and works for root), it is not a directory, not a device, not given twice,
  not one of the command's input files, and a figure has an extension matplotlib can write.
- :func:`write_all`: each result is written to a temporary file in the target's directory
  and moved over the target with ``os.replace`` only when complete, so a failed write
  (a full disk, a vanished directory) never leaves a half-written file; a failure of one
  target does not stop the others.

Every problem found before the computation is a :class:`~hubbeam.io.scenario.ScenarioError`
naming the option (exit status 2); a failed write is an :class:`OutputError` (exit status 1).
"""

from __future__ import annotations

import contextlib
import os
import stat
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from hubbeam.errors import ScenarioError

#: a scenario or measured file larger than this is not read (a scenario is a few kB)
MAX_INPUT_BYTES = 4 * 2**20
#: longest output file name: 255 bytes (NAME_MAX) less what the temporary file's name adds
MAX_NAME_BYTES = 230


class OutputError(Exception):
    """A result could not be written (the message names the option, the file and the reason)."""


def check_input_file(path, what: str = "scenario file", max_bytes: int = MAX_INPUT_BYTES) -> Path:
    """``path`` as a Path when it names a readable regular text file of at most ``max_bytes``;
    ScenarioError (one line naming the file) otherwise."""
    if not isinstance(path, (str, os.PathLike)):
        raise ScenarioError(f"{what}: expected a path (got {type(path).__name__} {path!r})")
    text = os.fspath(path)
    if isinstance(text, bytes) or not text or "\0" in text:
        raise ScenarioError(f"{what}: not a usable file name ({text!r})")
    p = Path(text)
    try:
        st = p.stat()
    except FileNotFoundError:
        raise ScenarioError(f"{p}: no such file") from None
    except OSError as exc:
        raise ScenarioError(f"{p}: cannot read ({exc.strerror or exc.__class__.__name__})") from None
    if stat.S_ISDIR(st.st_mode):
        raise ScenarioError(f"{p}: is a directory, not a {what}")
    if not stat.S_ISREG(st.st_mode):
        raise ScenarioError(f"{p}: not a regular file (a device, pipe or socket cannot be a {what})")
    if st.st_size > max_bytes:
        raise ScenarioError(f"{p}: {st.st_size / 2**20:.1f} MiB is too large for a {what} "
                            f"(at most {max_bytes / 2**20:.0f} MiB)")
    try:
        with open(p, "rb") as f:
            data = f.read(max_bytes + 1)
    except OSError as exc:
        raise ScenarioError(f"{p}: cannot read ({exc.strerror or exc.__class__.__name__})") from None
    if len(data) > max_bytes:
        raise ScenarioError(f"{p}: too large for a {what} (at most {max_bytes / 2**20:.0f} MiB)")
    if b"\0" in data:
        raise ScenarioError(f"{p}: not a text file (it contains NUL bytes), not a {what}")
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ScenarioError(f"{p}: not UTF-8 text (byte {exc.start}), not a {what}") from None
    return p


def figure_formats() -> list[str]:
    """File extensions matplotlib can save figures as (without importing pyplot)."""
    import shutil

    import matplotlib
    from matplotlib.backend_bases import FigureCanvasBase

    formats = set(FigureCanvasBase.get_supported_filetypes())
    if shutil.which(str(matplotlib.rcParams.get("pgf.texsystem", "xelatex"))) is None:
        formats.discard("pgf")  # needs a TeX installation
    return sorted(formats)


@dataclass
class Target:
    """One output of a command: ``option`` as the user wrote it ("-o", "--csv", ...), the
    path, and its kind: "file", "figure" or "directory"."""

    option: str
    path: str
    kind: str = "file"
    label: str = field(default="")

    def __post_init__(self):
        self.label = f"{self.option} {self.path}"


def _probe_directory(directory: Path, label: str) -> None:
    """ScenarioError unless a file can be created in ``directory`` (the real test: permissions,
    read-only file systems, quotas on inodes)."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".hubbeam-probe-", dir=directory)
    except OSError as exc:
        raise ScenarioError(f"{label}: cannot write in directory {directory} "
                            f"({exc.strerror or exc.__class__.__name__})") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)


def _same(a: str, b: str) -> bool:
    if os.path.realpath(a) == os.path.realpath(b):
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def check_outputs(targets: list[Target], inputs: list[tuple[str, object]] = ()) -> list[Target]:
    """Check every given output target before any computation; returns the targets that are
    set (path not None). ``inputs``: (what, path) of the files the command reads, which must
    not be overwritten. Raises ScenarioError naming the option."""
    given = []
    for t in targets:
        if t.path is None:
            continue
        label = t.label
        if not isinstance(t.path, str) or not t.path.strip():
            raise ScenarioError(f"{t.option}: empty file name")
        if "\0" in t.path:
            raise ScenarioError(f"{t.option}: the file name contains a NUL character")
        try:
            _check_target(t)
        except OSError as exc:  # a name the file system refuses (too long, a loop of links, ...)
            raise ScenarioError(f"{label}: not a usable path ({exc.strerror or exc.__class__.__name__})") from None
        for other in given:
            if _same(other.path, t.path):
                raise ScenarioError(f"{t.option}: {t.path} is also the target of {other.option} (give two different files)")
        for what, path in inputs:
            if path is not None and os.path.exists(t.path) and _same(os.fspath(path), t.path):
                raise ScenarioError(f"{label}: is the {what}; it would be overwritten")
        given.append(t)
    return given


def _check_target(t: Target) -> None:
    """The checks of one set target (:func:`check_outputs`); OSError from the file system passes."""
    label = t.label
    p = Path(t.path)
    if t.kind == "figure":
        ext = p.suffix.lower().lstrip(".")
        formats = figure_formats()
        if not ext:
            raise ScenarioError(f"{label}: no file extension, so no figure format (use one of {', '.join(formats)})")
        if ext not in formats:
            raise ScenarioError(f"{label}: matplotlib cannot write .{ext} figures (use one of {', '.join(formats)})")
    if t.kind == "directory" and p.is_symlink() and not p.exists():
        raise ScenarioError(f"{label}: is a link to {os.readlink(p)}, which does not exist")
    if t.kind == "directory":
        if p.exists():
            if not p.is_dir():
                raise ScenarioError(f"{label}: exists and is not a directory")
            _probe_directory(p, label)
        else:
            parent = p.absolute().parent
            if not parent.is_dir():
                raise ScenarioError(f"{label}: directory {parent} does not exist")
            _probe_directory(parent, label)
    else:
        if p.is_dir():
            raise ScenarioError(f"{label}: is a directory (give a file name)")
        if p.exists() and not p.is_file():
            raise ScenarioError(f"{label}: exists and is not a regular file (a device or pipe is not a result file)")
        if p.exists() and not os.access(p, os.W_OK):
            raise ScenarioError(f"{label}: the file exists and is read-only")
        if len(os.fsencode(Path(os.path.realpath(p)).name)) > MAX_NAME_BYTES:
            raise ScenarioError(f"{label}: file name too long (at most {MAX_NAME_BYTES} bytes)")
        parent = Path(os.path.realpath(p)).parent  # a link is written through (atomic_path): where it points
        if not parent.exists():
            raise ScenarioError(f"{label}: directory {parent} does not exist"
                                + (f" ({p} is a link to {os.readlink(p)})" if p.is_symlink() else ""))
        if not parent.is_dir():
            raise ScenarioError(f"{label}: {parent} is not a directory")
        _probe_directory(parent, label)


def check_inside(option: str, directory, names) -> None:
    """ScenarioError naming ``option`` when one of the files a command will write into
    ``directory`` (``names``) is there already as something a file cannot replace (a
    directory, a device, a link to nowhere): found before the computation, not after it."""
    d = Path(directory)
    if not d.is_dir():
        return
    wanted = set(names)
    for entry in os.scandir(d):
        if entry.name in wanted and not (entry.is_file() and not entry.is_symlink() or
                                         entry.is_symlink() and os.path.isfile(entry.path)):
            what = "a directory" if entry.is_dir() else "a link to nowhere" if entry.is_symlink() else "not a regular file"
            raise ScenarioError(f"{option} {d}: {entry.name} is there already and is {what}, so it cannot be written")


@contextlib.contextmanager
def atomic_path(path):
    """A temporary path next to ``path`` (with the same extension, for writers that choose
    the format from it); moved over ``path`` when the block ends normally, removed otherwise.
    A symbolic link is followed: the file it points to is replaced, the link stays."""
    path = Path(os.path.realpath(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".part{path.suffix}", dir=path.absolute().parent)
    os.close(fd)
    try:
        yield tmp
        fd = os.open(tmp, os.O_RDONLY)
        try:
            os.fsync(fd)  # the data is on disk before the name points at it
        finally:
            os.close(fd)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _reason(exc: BaseException) -> str:
    """A short reason for a failed write: the OS error if there is one in the chain."""
    seen = exc
    while seen is not None:
        if isinstance(seen, OSError) and seen.strerror:
            return seen.strerror
        seen = seen.__cause__ or seen.__context__
    text = str(exc).splitlines()[0] if str(exc) else ""
    return f"{exc.__class__.__name__}: {text}"[:200] if text else exc.__class__.__name__


def write_one(target: Target, writer) -> None:
    """``writer(tmp_path)`` then move into place; OutputError (one line) if it fails."""
    try:
        with atomic_path(target.path) as tmp:
            writer(tmp)
    except Exception as exc:
        raise OutputError(f"{target.label}: cannot write ({_reason(exc)})") from exc


def write_all(jobs: list[tuple[Target, object]], interruptible: bool = False) -> tuple[list[str], list[str]]:
    """Write every (target, writer) job, each atomically; a failed one does not stop the
    others. Returns (paths written, one-line error messages). Signals that arrive while
    writing are held (see :mod:`hubbeam.interrupt`): the caller raises or drops them.
    ``interruptible``: the writers are themselves the long computation (a movie rendered
    frame by frame), so a signal stops them at once; the file being written is removed and
    :class:`~hubbeam.interrupt.Interrupted` passes to the caller."""
    from hubbeam import interrupt

    written, errors = [], []
    with (contextlib.nullcontext() if interruptible else interrupt.deferred()):
        for target, writer in jobs:
            try:
                write_one(target, writer)
                written.append(target.path)
            except OutputError as exc:
                errors.append(str(exc))
    return written, errors
