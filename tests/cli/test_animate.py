"""hubbeam run --state, hubbeam animate and hubbeam vtk on the command line: files made and read back,
bad input as one line with exit status 2."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from PIL import Image

from hubbeam.io.state import read_state
from tests.cli.helpers import EXAMPLES, assert_contract, cli, no_temporary_files

SHORT = ["--set", "analysis.t_end=0.05", "--set", "analysis.output_dt=0.01"]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """exp1 on 2 elements (ANCF) and rotor3 (three blades) with --state, and exp1 without."""
    d = tmp_path_factory.mktemp("runs")
    out = {}
    for name, extra in (("exp1", ["--set", "beam.elements=2"]), ("rotor3", []),
                        ("ffr", ["--set", "beam.elements=2", "--set", 'beam.formulation="ffr"'])):
        scenario = EXAMPLES / f"{'exp1' if name == 'ffr' else name}.toml"
        code, _, err = cli("run", scenario, "-o", d / f"{name}.nc", "--state", *SHORT, *extra)
        assert code == 0, err
        out[name] = d / f"{name}.nc"
    code, _, err = cli("run", EXAMPLES / "exp1.toml", "-o", d / "plain.nc", "--csv", d / "plain.csv", *SHORT,
                       "--set", "beam.elements=2")
    assert code == 0, err
    out["plain"] = d / "plain.nc"
    return out


def test_state_needs_a_netcdf_output(tmp_path):
    code, out, err = cli("run", EXAMPLES / "exp1.toml", "--state", "--csv", tmp_path / "x.csv", *SHORT)
    assert_contract(code, out, err)
    assert code == 2 and "--state" in err and "-o" in err
    assert not (tmp_path / "x.csv").exists()  # refused before computing


@pytest.mark.parametrize("name", ["exp1", "rotor3", "ffr"])
def test_a_gif_has_one_frame_per_stored_time(runs, tmp_path, name):
    movie = tmp_path / "movie.gif"
    code, out, err = cli("animate", runs[name], "-o", movie)
    assert_contract(code, out, err)
    assert code == 0, err
    with Image.open(movie) as im:
        assert im.n_frames == 6  # t = 0, 0.01, ..., 0.05
    assert "6 frames (t = 0 to 0.05 s)" in out
    code, out, err = cli("animate", runs[name], "-o", movie, "--stride", "4", "--color", "none", "--fps", "5")
    assert code == 0, err
    with Image.open(movie) as im:
        assert im.n_frames == 2  # t = 0 and 0.04
    assert "2 frames (t = 0 to 0.04 s)" in out  # the times drawn, not the times stored
    code, out, err = cli("animate", runs[name], "-o", movie, "--stride", "100")
    assert code == 0, err
    assert "1 frame (t = 0 s)" in out
    assert no_temporary_files(tmp_path)


def test_an_mp4_is_written_with_the_packaged_ffmpeg(runs, tmp_path):
    pytest.importorskip("imageio_ffmpeg")
    movie = tmp_path / "movie.mp4"
    code, _, err = cli("animate", runs["rotor3"], "-o", movie, "--color", "deflection")
    assert code == 0, err
    assert movie.read_bytes()[4:8] == b"ftyp"  # an MP4 (ISO base media) file


def test_mp4_without_ffmpeg_is_one_line(runs, tmp_path, monkeypatch):
    import hubbeam.animate

    monkeypatch.setattr(hubbeam.animate, "find_ffmpeg", lambda: None)
    code, out, err = cli("animate", runs["exp1"], "-o", tmp_path / "movie.mp4")
    assert_contract(code, out, err)
    assert code == 2 and "ffmpeg" in err and "video" in err
    assert not (tmp_path / "movie.mp4").exists()


@pytest.mark.parametrize("args, key", [
    (["--color", "rainbow"], "--color"), (["--stride", "0"], "--stride"), (["--fps", "0"], "--fps"),
    (["-o", "movie.avi"], "-o"),
])
def test_bad_animate_options_are_one_line(runs, tmp_path, args, key):
    argv = ["animate", runs["exp1"], "-o", tmp_path / "movie.gif"] + args
    if args[0] == "-o":
        argv = ["animate", runs["exp1"], "-o", tmp_path / args[1]]
    code, out, err = cli(*argv)
    assert_contract(code, out, err)
    assert code == 2 and key in err


@pytest.mark.parametrize("command, target", [("animate", "movie.gif"), ("vtk", "series")])
def test_a_file_without_state_says_run_it_with_state(runs, tmp_path, command, target):
    code, out, err = cli(command, runs["plain"], "-o", tmp_path / target)
    assert_contract(code, out, err)
    assert code == 2 and "run it with --state" in err
    assert not (tmp_path / target).exists()


def test_vtk_series_reads_back_and_is_not_overwritten_silently(runs, tmp_path):
    state = read_state(runs["rotor3"])
    target = tmp_path / "series"
    code, out, err = cli("vtk", runs["rotor3"], "-o", target)
    assert code == 0, err
    every = ET.parse(target / "rotor3.pvd").getroot().find("Collection").findall("DataSet")
    rows = [r for r in every if r.get("part") == "0"]  # the beams; part 1: the rigid bodies
    bodies = [r for r in every if r.get("part") == "1"]
    assert [float(r.get("timestep")) for r in rows] == [float(r.get("timestep")) for r in bodies] == state.times.tolist()
    assert "and 4 rigid bodies" in out  # the hub and the three tip masses
    for row in bodies:
        assert sorted(set(np.concatenate(meshio.read(target / row.get("file")).cell_data["body"]))) == [0, 1, 2, 3]
    points = 2 * sum(b.stations.size for b in state.beams)
    for i, row in enumerate(rows):
        mesh = meshio.read(target / row.get("file"))
        assert mesh.points.shape == (points, 3)
        strain = mesh.point_data["surface_strain"]
        stored = np.concatenate([b.surface_strain[i] for b in state.beams])
        assert (strain.min(), strain.max()) == (stored.min(), stored.max())
    assert sorted(p.name for p in target.iterdir()) == sorted(["rotor3.pvd"] + [r.get("file") for r in every])
    before = (target / "rotor3_00000.vtu").stat().st_mtime_ns
    code, out, err = cli("vtk", runs["rotor3"], "-o", target)
    assert_contract(code, out, err)
    assert code == 2 and "--force" in err
    assert (target / "rotor3_00000.vtu").stat().st_mtime_ns == before
    (target / "rotor3_00099.vtu").write_text("an older, longer series")
    (target / "rotor3_bodies_00099.vtu").write_text("its bodies")
    code, out, err = cli("vtk", runs["rotor3"], "-o", target, "--force")
    assert code == 0, err
    assert not (target / "rotor3_00099.vtu").exists() and not (target / "rotor3_bodies_00099.vtu").exists()
    assert no_temporary_files(target)


def test_animate_scale_and_view(runs, tmp_path):
    movie = tmp_path / "m.gif"
    code, out, err = cli("animate", runs["rotor3"], "-o", movie, "--scale", "50", "--view", "top", "--stride", "5")
    assert_contract(code, out, err)
    assert code == 0, err
    code, out, err = cli("animate", runs["rotor3"], "-o", movie, "--view", "30,-120", "--stride", "5")
    assert code == 0, err
    for args, message in ((["--view", "above"], "--view: unknown view 'above'"), (["--scale", "0"], "--scale: must be > 0"),
                          (["--scale", "inf"], "--scale: must be > 0")):
        code, out, err = cli("animate", runs["rotor3"], "-o", tmp_path / "x.gif", *args)
        assert_contract(code, out, err)
        assert code == 2 and message in err, err
        assert not (tmp_path / "x.gif").exists()
