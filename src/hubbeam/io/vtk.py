"""A run's recorded state as a ParaView time series: ``DIR/NAME.pvd`` and one ``.vtu`` per output time.

Each ``NAME_NNNNN.vtu`` (meshio) holds every beam as a ribbon of quadrilaterals: at each
span station two points, the centre line -+ (b/2) m (b the station's width, m the section's
unit vector along it), the first on the -m edge; station i of a beam gives points 2i and
2i + 1, and the segment between stations i and i + 1 the quad (2i, 2i + 1, 2i + 3, 2i + 2).
Point data: ``displacement`` (m, global: the centre line's displacement from the undeformed
beam turned with the hub, :meth:`hubbeam.io.state.BeamTrack.displacement`, the same on both
edge points of a station) and ``surface_strain`` (1, the upper surface's axial strain at the
station); cell data ``beam`` (the beam's index, 0-based); field data ``TimeValue`` (s). A hinge
(a beam's root on a revolute joint) is one more point at the root's centre with a vertex cell
(its ``beam``, the child's index), so that ParaView draws it as a joint (Glyph it).
``NAME.pvd`` (a ParaView Data collection) lists the files with their times.

The rigid bodies (:mod:`hubbeam.io.bodies`: the hub and every tip body) are a second block of
the series: ``NAME_bodies_NNNNN.vtu`` at each output time, listed in the .pvd as part 1 (the
beams are part 0), each body its glyph's surface (quads; the hub's disc caps as polygons)
and its three axes (lines from its origin, 1.5 times its largest half side long). Cell data
``body`` (the body's index: 0 the hub, then the tip bodies in the beams' order, named in
the .pvd's comment) and ``axis`` (-1 on the surface, 0, 1, 2 on
the lines along the body's first, second, third axis).
"""

from __future__ import annotations

import contextlib
import os
import re
from xml.sax.saxutils import quoteattr

import numpy as np

from hubbeam.io.bodies import rigid_bodies
from hubbeam.io.state import RunState

#: digits of the output-time index in the .vtu file names
INDEX_DIGITS = 5


def series_name(state: RunState) -> str:
    """The file name stem of a run's series: its scenario name with anything but letters,
    digits, '-', '_' and '.' replaced by '_'."""
    return re.sub(r"[^A-Za-z0-9_.-]", "_", state.name).strip(".") or "run"


def file_names(state: RunState) -> tuple[str, list[str]]:
    """(the .pvd name, the .vtu names in time order) of a run's series."""
    stem = series_name(state)
    return f"{stem}.pvd", [f"{stem}_{i:0{INDEX_DIGITS}d}.vtu" for i in range(state.times.size)]


def body_file_names(state: RunState) -> list[str]:
    """The rigid bodies' .vtu names in time order (see the module doc)."""
    stem = series_name(state)
    return [f"{stem}_bodies_{i:0{INDEX_DIGITS}d}.vtu" for i in range(state.times.size)]


def bodies_mesh(bodies, i: int, time: float):
    """The meshio.Mesh of the rigid bodies (:func:`hubbeam.io.bodies.rigid_bodies`) at output
    time i, ``time`` s (see the module doc)."""
    import meshio

    points, blocks = [], {}
    offset = 0
    for k, body in enumerate(bodies):
        vertices, faces = body.surface(i)
        axes = body.axes(i)
        points += [vertices, axes]
        for face in faces:
            kind = {3: "triangle", 4: "quad"}.get(face.size, "polygon")
            blocks.setdefault(kind, []).append((offset + face, k, -1))
        base = offset + vertices.shape[0]
        for a in range(3):
            blocks.setdefault("line", []).append((np.array([base, base + 1 + a]), k, a))
        offset += vertices.shape[0] + 4
    cells, body_ids, axis_ids = [], [], []
    for kind, rows in blocks.items():
        if kind == "polygon":  # one block per polygon size (meshio writes them as VTK polygons)
            for size in sorted({len(r[0]) for r in rows}):
                same = [r for r in rows if len(r[0]) == size]
                cells.append(("polygon", np.array([r[0] for r in same])))
                body_ids.append(np.array([r[1] for r in same], dtype=np.int32))
                axis_ids.append(np.array([r[2] for r in same], dtype=np.int32))
            continue
        cells.append((kind, np.array([r[0] for r in rows])))
        body_ids.append(np.array([r[1] for r in rows], dtype=np.int32))
        axis_ids.append(np.array([r[2] for r in rows], dtype=np.int32))
    return meshio.Mesh(np.concatenate(points), cells, cell_data={"body": body_ids, "axis": axis_ids},
                       field_data={"TimeValue": np.array([time])})


def ribbon_mesh(state: RunState, i: int):
    """The meshio.Mesh of output time i (see the module doc)."""
    import meshio

    points, quads, beam_ids, displacement, strain = [], [], [], [], []
    offset = 0
    for k, beam in enumerate(state.beams):
        half = 0.5 * beam.width[:, None] * beam.m[i]
        centre = beam.centre_line[i]
        n = centre.shape[0]
        points.append(np.stack([centre - half, centre + half], axis=1).reshape(2 * n, 3))
        s = offset + 2 * np.arange(n - 1)
        quads.append(np.column_stack([s, s + 1, s + 3, s + 2]))
        beam_ids.append(np.full(n - 1, k, dtype=np.int32))
        disp = state.displacement(k, slice(i, i + 1))[0]
        displacement.append(np.repeat(disp, 2, axis=0))
        strain.append(np.repeat(beam.surface_strain[i], 2))
        offset += 2 * n
    cells = [("quad", np.concatenate(quads))]
    ids = [np.concatenate(beam_ids)]
    if state.joints:  # a hinge: the root's centre, one vertex each
        for k in state.joints:
            beam = state.beams[k]
            points.append(beam.centre_line[i, :1])
            displacement.append(state.displacement(k, slice(i, i + 1))[0][:1])
            strain.append(beam.surface_strain[i, :1])
        cells.append(("vertex", offset + np.arange(len(state.joints)).reshape(-1, 1)))
        ids.append(np.array(state.joints, dtype=np.int32))
    return meshio.Mesh(np.concatenate(points), cells,
                       point_data={"displacement": np.concatenate(displacement),
                                   "surface_strain": np.concatenate(strain)},
                       cell_data={"beam": ids},
                       field_data={"TimeValue": np.array([state.times[i]])})  # written by write_vtu


def write_vtu(state: RunState, i: int, path) -> None:
    """Output time i's beams as a .vtu file (base64 binary, uncompressed), with the field data
    ``TimeValue`` (meshio reads field data but does not write it: it is added here)."""
    _write_mesh(ribbon_mesh(state, i), path)


def write_bodies_vtu(state: RunState, bodies, i: int, path) -> None:
    """Output time i's rigid bodies (``bodies``: :func:`hubbeam.io.bodies.rigid_bodies` of the
    state, computed once for the series) as a .vtu file (as :func:`write_vtu`)."""
    _write_mesh(bodies_mesh(bodies, i, float(state.times[i])), path)


def _write_mesh(mesh, path) -> None:
    import meshio

    meshio.write(str(path), mesh, file_format="vtu", binary=True, compression=None)
    with open(path, encoding="ascii") as f:
        text = f.read()
    field = "".join(f'<DataArray type="Float64" Name={quoteattr(name)} NumberOfTuples="{np.size(values)}" '
                    f'format="ascii">{" ".join(repr(float(v)) for v in np.ravel(values))}</DataArray>\n'
                    for name, values in mesh.field_data.items())
    text = text.replace("<UnstructuredGrid>\n", f"<UnstructuredGrid>\n<FieldData>\n{field}</FieldData>\n", 1)
    with open(path, "w", encoding="ascii") as f:
        f.write(text)


def pvd_text(state: RunState) -> str:
    """The ParaView collection of a run's .vtu files with their times (s): the beams (part 0)
    and the rigid bodies (part 1)."""
    _, vtus = file_names(state)
    rows = "\n".join(f'    <DataSet timestep="{t!r}" group="" part="{part}" file={quoteattr(name)}/>'
                     for t, beams, bodies in zip(state.times.tolist(), vtus, body_file_names(state))
                     for part, name in ((0, beams), (1, bodies)))
    names = ", ".join(f"{k} {b.name}" for k, b in enumerate(rigid_bodies(state)))
    comment = f"  <!-- part 0: the beams; part 1: the rigid bodies (cell data body: {names}) -->\n"
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"{comment}  <Collection>\n{rows}\n  </Collection>\n</VTKFile>\n")


class SeriesLocked(Exception):
    """Another live process holds the series' lock (:func:`series_lock`); ``pid`` is its
    process id (0 when it cannot be read)."""

    def __init__(self, path: str, pid: int):
        super().__init__(path)
        self.path, self.pid = path, pid


def lock_name(state: RunState) -> str:
    """The lock file that marks a series as being written (:func:`series_lock`)."""
    return f".{series_name(state)}.hubbeam-lock"


@contextlib.contextmanager
def series_lock(directory, state: RunState):
    """Hold the series of ``state`` in ``directory`` for one writer: a lock file created with
    O_EXCL (atomic: of two exports of one series name into one directory, exactly one gets
    it), holding the writer's process id and removed at the end. A lock whose process is gone
    (a writer killed with SIGKILL) is taken over. :class:`SeriesLocked` when another live
    process holds it; OSError when the lock file cannot be made."""
    path = os.path.join(os.fspath(directory), lock_name(state))
    for _ in range(2):
        try:
            fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            break
        except FileExistsError:
            try:
                with open(path, encoding="ascii") as f:
                    pid = int(f.read().strip() or 0)
            except (OSError, ValueError):
                pid = 0  # being written this very moment, or not ours: treat as held
            if pid > 0 and not _alive(pid):
                with contextlib.suppress(FileNotFoundError):
                    os.unlink(path)  # the writer is gone: take the lock over
                continue
            raise SeriesLocked(path, pid) from None
    else:  # another process took the stale lock over first
        raise SeriesLocked(path, 0)
    try:
        os.write(fd, str(os.getpid()).encode())
        os.close(fd)
        yield path
    finally:
        with contextlib.suppress(OSError):
            os.unlink(path)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # exists, owned by someone else
        return True
    return True
