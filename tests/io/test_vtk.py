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
    assert names == [f"rotor3_{i:05d}.vtu" for i in range(state.times.size)]
    assert vtk.body_file_names(state) == [f"rotor3_bodies_{i:05d}.vtu" for i in range(state.times.size)]
    assert [r.get("file") for r in rows if r.get("part") == "0"] == names
    assert [r.get("file") for r in rows if r.get("part") == "1"] == vtk.body_file_names(state)
    assert [float(r.get("timestep")) for r in rows] == np.repeat(state.times, 2).tolist()


def test_the_bodies_file_holds_the_hub_and_every_tip_body_at_their_poses(state, tmp_path):
    """rotor3's hub and its three 0.05 kg tip masses: each glyph's vertices about the body's
    pose (the hub a disc of its radius turned by theta, a tip body a box about its centre of
    mass, the tip centroid plus the offset in the tip section frame), its axes as lines."""
    from hubbeam.io.bodies import Glyph, rigid_bodies
    from hubbeam.io.state import hub_rotation

    bodies = rigid_bodies(state)
    assert [b.name for b in bodies] == ["hub", "tip_body_blade1", "tip_body_blade2", "tip_body_blade3"]
    i = state.times.size - 1
    path = tmp_path / "b.vtu"
    vtk.write_bodies_vtu(state, bodies, i, path)
    mesh = meshio.read(path)
    assert mesh.field_data["TimeValue"][0] == state.times[i]
    body = np.concatenate(mesh.cell_data["body"])
    axis = np.concatenate(mesh.cell_data["axis"])
    assert sorted(set(body.tolist())) == [0, 1, 2, 3]
    assert np.count_nonzero(axis >= 0) == 3 * len(bodies)  # three axis lines per body
    hub = bodies[0]
    assert hub.glyph is Glyph.DISC and hub.half_size[0] == pytest.approx(state.hub_radius)
    np.testing.assert_allclose(hub.rotation[i], hub_rotation(state.hub_angle[i])[0])
    for k, beam in enumerate(state.beams):
        tip = bodies[1 + k]
        R = tip.rotation[i]
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) == pytest.approx(1.0)
        np.testing.assert_allclose(R[:, 1], beam.m[i, -1])
        np.testing.assert_allclose(tip.position[i], beam.centre_line[i, -1] + R @ beam.tip_body["offset"], atol=1e-14)
        vertices, _ = tip.surface(i)
        np.testing.assert_allclose(np.linalg.norm(vertices - tip.position[i], axis=1),
                                   np.linalg.norm(tip.half_size), rtol=1e-12)


def test_a_tip_body_is_drawn_as_the_box_of_its_mass_and_inertia():
    """The spacecraft's 1 kg tip bodies are 100 x 100 x 50 mm boxes (the example's comment):
    their inertias m (b^2 + c^2) / 12, ... give those sides back; a point mass a cube."""
    from hubbeam.io.bodies import box_of_inertia

    np.testing.assert_allclose(2 * box_of_inertia(1.0, [1.0417e-3, 1.0417e-3, 1.6667e-3], 0.4), [0.1, 0.1, 0.05],
                               rtol=1e-3)
    np.testing.assert_allclose(box_of_inertia(0.5, [0.0, 0.0, 0.0], 0.04), [0.02, 0.02, 0.02])


def test_a_series_name_is_a_safe_file_name(state):
    from dataclasses import replace

    assert vtk.series_name(replace(state, name="a b/../c")) == "a_b_.._c"
    assert vtk.series_name(replace(state, name="..")) == "run"
