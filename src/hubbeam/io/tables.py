"""Time series tables (CSV) for the hub: a measured drive speed or angle, an applied torque.

A table is a text file of comma-separated values (``;`` or tab also accepted when the header has
no comma) with a header row naming the columns; blank lines and lines starting with ``#`` are
skipped. Column names are matched case-insensitively and may carry a unit in brackets,
``time (s)`` or ``omega [rad/s]``; other columns are ignored. Every problem becomes one
:class:`~hubbeam.errors.ScenarioError` line ``"{key}: {path}: reason"``.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from hubbeam.errors import ScenarioError
from hubbeam.system.laws import MIN_DRIVE_ROWS, MIN_SMOOTHED_ROWS, MIN_TORQUE_ROWS, DriveProfile, TorqueLaw

__all__ = ["MAX_TABLE_BYTES", "read_series", "read_drive_table", "read_torque_table"]

#: largest table file read (bytes)
MAX_TABLE_BYTES = 50 * 1024 * 1024
#: a cell's magnitude must stay below this (:data:`hubbeam.limits.MAGNITUDE_RANGE`, as every number of a scenario)
MAX_CELL = 1e150
#: consecutive times must be at least this far apart (s): the shortest step a run takes (:data:`hubbeam.limits.MIN_DT`)
MIN_TIME_STEP = 1e-9

_UNIT = re.compile(r"\s*[\(\[].*[\)\]]\s*$")


def _column_name(cell: str) -> str:
    return _UNIT.sub("", cell.strip()).strip().lower()


def _resolve(path: str | Path, base_dir: str | Path | None) -> Path:
    p = Path(path).expanduser()
    if base_dir is not None and not p.is_absolute():
        p = Path(base_dir).expanduser() / p
    return p


def read_columns(
    path: str | Path,
    key: str,
    required: Sequence[str],
    optional: Sequence[str] = (),
    *,
    base_dir: str | Path | None = None,
    min_rows: int = 2,
    max_bytes: int = MAX_TABLE_BYTES,
) -> tuple[Path, dict[str, np.ndarray], list[int]]:
    """(the file's path, {column: values}, the file line of each row) of a CSV table: every
    ``required`` column and those of ``optional`` that are present. Checks: the file exists and
    is at most ``max_bytes``; it is text with a header; the required columns are present; every
    cell of the columns read is a finite number of magnitude below :data:`MAX_CELL`; at least
    ``min_rows`` rows. Rows are numbered from 1 (the first data row) and the file line is given
    too. Arrays are float64, 1-D."""
    p = _resolve(path, base_dir)

    def fail(reason: str) -> ScenarioError:
        return ScenarioError(f"{key}: {p}: {reason}")

    # -- the file -----------------------------------------------------------------------------
    try:
        size = p.stat().st_size
    except FileNotFoundError:
        raise fail("file not found") from None
    except OSError as exc:
        raise fail(f"cannot read the file ({exc.strerror or exc})") from None
    if not p.is_file():
        raise fail("not a file")
    if size > max_bytes:
        raise fail(f"file is {size / 2**20:.1f} MB, larger than the {max_bytes / 2**20:g} MB limit for a table")
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise fail(f"cannot read the file ({exc.strerror or exc})") from None
    if b"\x00" in raw:
        raise fail("not a CSV text file (binary content)")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        try:
            text = raw.decode("latin-1")
        except UnicodeDecodeError:  # pragma: no cover - latin-1 decodes every byte
            raise fail("not a CSV text file") from None

    # -- the header ---------------------------------------------------------------------------
    lines = text.splitlines()
    numbered = [(n, line) for n, line in enumerate(lines, start=1)
                if line.strip() and not line.lstrip().startswith("#")]
    if not numbered:
        raise fail("empty file: expected a header row (" + ", ".join(required) + ")")
    header_line = numbered[0][1]
    delimiter = ","
    if "," not in header_line:
        delimiter = ";" if ";" in header_line else ("\t" if "\t" in header_line else ",")
    try:
        rows = list(csv.reader(io.StringIO("\n".join(line for _, line in numbered)), delimiter=delimiter))
    except csv.Error as exc:
        raise fail(f"not a CSV file ({exc})") from None
    names = [_column_name(c) for c in rows[0]]
    seen: set[str] = set()
    for name in names:
        if name and name in seen:
            raise fail(f"column {name!r} appears twice in the header")
        seen.add(name)
    for name in required:
        if name not in names:
            shown = ", ".join(repr(n) for n in names[:8]) + (", ..." if len(names) > 8 else "")
            raise fail(f"no {name!r} column in the header (found {shown}); expected a header row such as "
                       f"'{','.join(required)}'")
    wanted = list(required) + [c for c in optional if c in names]

    # -- the rows -----------------------------------------------------------------------------
    data = rows[1:]
    out = {name: np.empty(len(data)) for name in wanted}
    line_numbers = []
    for r, cells in enumerate(data):
        line_no = numbered[r + 1][0]
        line_numbers.append(line_no)
        where = f"row {r + 1} (line {line_no})"
        if len(cells) != len(names):
            raise fail(f"{where} has {len(cells)} cells, the header has {len(names)}")
        for col in wanted:
            cell = cells[names.index(col)].strip()
            try:
                x = float(cell)
            except ValueError:
                raise fail(f"{where}, column {col!r}: {cell!r} is not a number") from None
            if not math.isfinite(x):
                raise fail(f"{where}, column {col!r}: {cell!r} is not finite")
            if not abs(x) < MAX_CELL:
                raise fail(f"{where}, column {col!r}: {cell!r} is outside the range hubbeam computes with (magnitudes "
                           f"below {MAX_CELL:g}); check the value and its unit (SI)")
            out[col][r] = x
    if len(data) < min_rows:
        raise fail(f"the table needs at least {min_rows} rows, found {len(data)}")
    return p, out, line_numbers


def check_times(p: Path, key: str, t: np.ndarray, line_numbers: Sequence[int], rows: Sequence[int] | None = None) -> None:
    """Times t strictly increase, at least :data:`MIN_TIME_STEP` apart (``rows``: the 0-based
    row of each time in the file, default 0, 1, ...); one :class:`ScenarioError` naming the row
    and line otherwise."""
    rows = range(t.size) if rows is None else rows
    for r in range(1, t.size):
        row = rows[r]
        if t[r] <= t[r - 1]:
            what = "a duplicate time" if t[r] == t[r - 1] else "times are not increasing"
            raise ScenarioError(f"{key}: {p}: row {row + 1} (line {line_numbers[row]}): {what} ({float(t[r])!r} after "
                                f"{float(t[r - 1])!r})")
        if not t[r] - t[r - 1] >= MIN_TIME_STEP:
            raise ScenarioError(f"{key}: {p}: row {row + 1} (line {line_numbers[row]}): {float(t[r])!r} s is "
                                f"{t[r] - t[r - 1]:.3g} s after the row before, closer than {MIN_TIME_STEP:g} s, the "
                                "shortest step a run takes: no run resolves it")


def read_series(
    path: str | Path,
    key: str,
    columns: Sequence[str],
    *,
    base_dir: str | Path | None = None,
    min_rows: int = 2,
    start_at_zero: bool = False,
    max_bytes: int = MAX_TABLE_BYTES,
) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """(time, {column: values}) from a CSV table with a ``time`` column.

    ``columns`` are alternatives: exactly one of them must be present, e.g. ``("omega", "theta")``
    for a drive table or ``("torque",)`` for a torque table; the dict holds that one. A relative
    ``path`` is taken relative to ``base_dir`` when given. Checks: those of :func:`read_columns`;
    times strictly increase, at least :data:`MIN_TIME_STEP` apart (:func:`check_times`); with
    ``start_at_zero`` the first time is 0.
    """
    columns = tuple(c.lower() for c in columns)
    if not columns:
        raise ValueError("columns: give at least one column name")
    p, found, lines = read_columns(path, key, ("time",), columns, base_dir=base_dir, min_rows=0, max_bytes=max_bytes)
    present = [c for c in columns if c in found]
    if not present:
        want = " or ".join(repr(c) for c in columns)
        raise ScenarioError(f"{key}: {p}: no {want} column in the header")
    if len(present) > 1:
        raise ScenarioError(f"{key}: {p}: give one of the columns {' or '.join(repr(c) for c in present)}, not both")
    name = present[0]
    t = found["time"]
    if t.size < min_rows:
        raise ScenarioError(f"{key}: {p}: the table needs at least {min_rows} rows, found {t.size}")
    check_times(p, key, t, lines)
    if start_at_zero and t[0] != 0.0:
        raise ScenarioError(f"{key}: {p}: the first time must be 0 s (found {float(t[0])!r})")
    return t, {name: found[name]}


def read_drive_table(path: str | Path, key: str, *, base_dir: str | Path | None = None, interpolation: str = "spline",
                     smoothing: float | None = None) -> DriveProfile:
    """A ``table`` drive profile from a CSV with columns ``time`` (s) and ``omega`` (rad/s) or
    ``theta`` (rad), interpolated and smoothed as :meth:`DriveProfile.table` says. ``key`` names
    the file's key (``hub.drive.file``); the options are named beside it (``hub.drive.interpolation``)."""
    t, cols = read_series(path, key, ("omega", "theta"), base_dir=base_dir, min_rows=MIN_DRIVE_ROWS,
                          start_at_zero=True)
    (quantity, values), = cols.items()
    p = _resolve(path, base_dir)
    table = key.rsplit(".", 1)[0]
    if quantity == "theta" and values[0] != 0.0:
        raise ScenarioError(f"{key}: {p}: the first theta must be 0 rad, the initial configuration (found {float(values[0])!r})")
    if interpolation == "linear" and quantity == "theta":
        raise ScenarioError(f"{table}.interpolation: 'linear' is for an omega table, and {p} is a theta table (its "
                            "speed would step and its acceleration be infinite at every row); use 'spline', with "
                            "smoothing for a noisy one")
    if smoothing is not None and t.size < MIN_SMOOTHED_ROWS:
        raise ScenarioError(f"{table}.smoothing: {p} has {t.size} rows; smoothing needs at least {MIN_SMOOTHED_ROWS}")
    try:
        return DriveProfile.table(t, values, quantity, interpolation=interpolation, smoothing=smoothing)
    except ValueError as exc:  # pragma: no cover - read_series checks everything DriveProfile does
        raise ScenarioError(f"{key}: {p}: {exc}") from None


def read_torque_table(path: str | Path, key: str, *, base_dir: str | Path | None = None) -> TorqueLaw:
    """A ``table`` torque law from a CSV with columns ``time`` (s) and ``torque`` (N m)."""
    t, cols = read_series(path, key, ("torque",), base_dir=base_dir, min_rows=MIN_TORQUE_ROWS)
    try:
        return TorqueLaw.table(t, cols["torque"])
    except ValueError as exc:  # pragma: no cover - read_series checks everything TorqueLaw does
        raise ScenarioError(f"{key}: {_resolve(path, base_dir)}: {exc}") from None


#: the columns of a base's pose table besides time: O_b (m) and the rotation vector (rad)
POSE_COLUMNS = ("x", "y", "z", "rx", "ry", "rz")


def read_pose_table(path: str | Path, key: str, *, base_dir: str | Path | None = None):
    """A base's :class:`~hubbeam.system.base_laws.PoseTable` from a CSV with columns ``time``
    (s), ``x``, ``y``, ``z`` (m: the base origin, global) and ``rx``, ``ry``, ``rz`` (rad: the
    rotation vector of the base axes); at least 4 rows from t = 0. A rotation vector that jumps
    by more than pi between rows (the same attitude written as another vector: unwrap it) is
    refused naming the row."""
    from hubbeam.system.base_laws import MIN_POSE_ROWS, PoseTable

    columns = {}
    t = None
    for name in POSE_COLUMNS:
        t, cols = read_series(path, key, (name,), base_dir=base_dir, min_rows=MIN_POSE_ROWS, start_at_zero=True)
        columns[name] = cols[name]
    position = np.column_stack([columns[c] for c in POSE_COLUMNS[:3]])
    rotation = np.column_stack([columns[c] for c in POSE_COLUMNS[3:]])
    p = _resolve(path, base_dir)
    jumps = np.linalg.norm(np.diff(rotation, axis=0), axis=1)
    if np.any(jumps > np.pi):
        r = int(np.argmax(jumps > np.pi)) + 2
        raise ScenarioError(f"{key}: {p}: row {r}: the rotation vector jumps by {jumps[r - 2]:.4g} rad (more than pi) "
                            "from the row before: write the rotation continuously (unwrapped)")
    try:
        return PoseTable(t, position, rotation)
    except ValueError as exc:  # pragma: no cover - read_series checks everything PoseTable does
        raise ScenarioError(f"{key}: {p}: {exc}") from None


#: the columns of a load table: force (N or N/m) and moment (N m or N m/m) components, global or section axes
FORCE_COLUMNS = ("fx", "fy", "fz")
MOMENT_COLUMNS = ("mx", "my", "mz")


def read_tip_table(path: str | Path, key: str, columns: Sequence[str], *, base_dir: str | Path | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(times (s), values (nt, 3)) of a tip load table: a CSV with ``time`` and the three
    ``columns`` (:data:`FORCE_COLUMNS`, N, or :data:`MOMENT_COLUMNS`, N m), times increasing;
    one row is a constant load."""
    p, found, lines = read_columns(path, key, ("time",) + tuple(columns), base_dir=base_dir, min_rows=1)
    check_times(p, key, found["time"], lines)
    return found["time"], np.column_stack([found[c] for c in columns])


def read_span_table(path: str | Path, key: str, length: float, *, base_dir: str | Path | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x (m), times (s), values (nt, nx, 6): force (N/m) and moment (N m/m)) of a distributed
    load table: a CSV with ``x`` (m from the root, within [0, ``length``]), ``fx, fy, fz`` and
    optionally ``mx, my, mz`` (all three; absent: zero) and ``time``. Without ``time`` the rows
    are stations with x strictly increasing (at least 2); with ``time`` the rows come in blocks
    of one time each, times increasing from block to block, and every block has the stations of
    the first block, in the same order."""
    p, found, lines = read_columns(path, key, ("x",) + FORCE_COLUMNS, ("time",) + MOMENT_COLUMNS, base_dir=base_dir,
                                   min_rows=2)

    def fail(row: int, reason: str) -> ScenarioError:
        return ScenarioError(f"{key}: {p}: row {row + 1} (line {lines[row]}): {reason}")

    moments = [c for c in MOMENT_COLUMNS if c in found]
    if moments and len(moments) != 3:
        missing = [c for c in MOMENT_COLUMNS if c not in found]
        raise ScenarioError(f"{key}: {p}: give the moment columns mx, my and mz together (missing {', '.join(missing)})")
    x_all = found["x"]
    columns = [found[c] for c in FORCE_COLUMNS] + [found[c] if c in found else np.zeros(x_all.size)
                                                   for c in MOMENT_COLUMNS]
    table = np.column_stack(columns)
    slack = 1e-9 * length
    for r, x in enumerate(x_all):
        if not -slack <= x <= length + slack:
            raise fail(r, f"x = {float(x)!r} m is outside the beam's span [0, {length:g}] m")
    x_all = np.clip(x_all, 0.0, length)
    if "time" not in found:
        blocks = [np.arange(x_all.size)]
        times = np.zeros(1)
    else:
        t = found["time"]
        starts = [0] + [r for r in range(1, t.size) if t[r] != t[r - 1]]
        blocks = [np.arange(a, b) for a, b in zip(starts, starts[1:] + [t.size])]
        times = t[starts]
        check_times(p, key, times, lines, starts)
    stations = x_all[blocks[0]]
    if stations.size < 2:
        raise fail(int(blocks[0][0]), "a block of one time needs at least 2 stations (x values)")
    for block in blocks:
        xs = x_all[block]
        for j in range(1, xs.size):
            if not xs[j] > xs[j - 1]:
                raise fail(int(block[j]), f"x values are not increasing ({float(xs[j])!r} after {float(xs[j - 1])!r})")
        if xs.size != stations.size or np.any(xs != stations):
            raise fail(int(block[0]), "every time needs the stations (x values) of the first time, in the same order")
    values = np.stack([table[block] for block in blocks])
    return stations, times, values
