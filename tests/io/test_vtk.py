"""hubbeam.io.vtk: the ParaView series of a run with a recorded state, read back with meshio."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from hubbeam import api
from hubbeam.io import vtk
from hubbeam.io.results import write_trajectory_netcdf
from hubbeam.io.scenario import load_example
from hubbeam.io.state import read_state


@pytest.fixture(scope="module")
def state(tmp_path_factory):
    scenario = load_example("rotor3", ["analysis.t_end=0.06", "analysis.output_dt=0.02", "beams[1].elements=3"])
    traj, failure = api.run(scenario, state=True)
    assert failure is None
    path = tmp_path_factory.mktemp("vtk") / "rotor3.nc"
    write_trajectory_netcdf(traj, scenario, path)
    return read_state(path)


def test_each_vtu_is_the_ribbons_of_every_beam(state, tmp_path):
    stations = [b.stations.size for b in state.beams]
    assert stations == [17, 13, 17]  # blade2 has 3 elements: stations differ per beam
    for i, t in enumerate(state.times):
        path = tmp_path / f"{i}.vtu"
        vtk.write_vtu(state, i, path)
        mesh = meshio.read(path)
        assert mesh.points.shape == (2 * sum(stations), 3)
        assert mesh.cells_dict["quad"].shape == (sum(stations) - len(stations), 4)
        assert mesh.field_data["TimeValue"][0] == t
        strain = mesh.point_data["surface_strain"]
        stored = np.concatenate([b.surface_strain[i] for b in state.beams])
        assert (strain.min(), strain.max()) == (stored.min(), stored.max())
        np.testing.assert_array_equal(np.bincount(mesh.cell_data["beam"][0]), np.array(stations) - 1)
        # the two edge points of a station are b apart, their middle is the stored centre line
        start = 0
        for k, beam in enumerate(state.beams):
            pts = mesh.points[start : start + 2 * beam.stations.size].reshape(-1, 2, 3)
            np.testing.assert_allclose(0.5 * (pts[:, 0] + pts[:, 1]), beam.centre_line[i], atol=1e-12)
            np.testing.assert_allclose(np.linalg.norm(pts[:, 1] - pts[:, 0], axis=1), beam.width, rtol=1e-12)
            disp = mesh.point_data["displacement"][start : start + 2 * beam.stations.size : 2]
            np.testing.assert_allclose(disp, state.displacement(k)[i], atol=1e-12)
            start += 2 * beam.stations.size


def test_the_pvd_lists_every_file_with_its_time(state):
    root = ET.fromstring(vtk.pvd_text(state))
    rows = root.find("Collection").findall("DataSet")
    _, names = vtk.file_names(state)
    assert [r.get("file") for r in rows] == names == [f"rotor3_{i:05d}.vtu" for i in range(state.times.size)]
    assert [float(r.get("timestep")) for r in rows] == state.times.tolist()


def test_a_series_name_is_a_safe_file_name(state):
    from dataclasses import replace

    assert vtk.series_name(replace(state, name="a b/../c")) == "a_b_.._c"
    assert vtk.series_name(replace(state, name="..")) == "run"
