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
"""

from __future__ import annotations

import re
from xml.sax.saxutils import quoteattr

import numpy as np

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
    """Output time i as a .vtu file (base64 binary, uncompressed), with the field data
    ``TimeValue`` (meshio reads field data but does not write it: it is added here)."""
    import meshio

    mesh = ribbon_mesh(state, i)
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
    """The ParaView collection of a run's .vtu files with their times (s)."""
    _, vtus = file_names(state)
    rows = "\n".join(f'    <DataSet timestep="{t!r}" group="" part="0" file={quoteattr(name)}/>'
                     for t, name in zip(state.times.tolist(), vtus))
    return ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f"  <Collection>\n{rows}\n  </Collection>\n</VTKFile>\n")
