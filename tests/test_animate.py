"""hubbeam.animate: what is drawn, checked on a made-up state (no run needed)."""

import numpy as np
import pytest

from hubbeam import animate
from hubbeam.io.state import BeamTrack, RunState


def _state(nt=5):
    """One straight beam along i_h from R = 0.3 to 1.3 m, width 0.1 m along j0 ... turning with the hub."""
    theta = np.linspace(0.0, 1.0, nt)
    xs = np.linspace(0.0, 1.0, 5)
    i_h = np.stack([np.cos(theta), np.zeros(nt), np.sin(theta)], axis=1)
    line = (0.3 + xs)[None, :, None] * i_h[:, None, :]
    m = np.broadcast_to([0.0, 1.0, 0.0], line.shape).copy()
    n = np.cross(i_h[:, None, :], m)
    beam = BeamTrack("b", "ancf", xs, np.full(5, 0.1), np.full(5, 0.01), line[0], line, m, n,
                     np.tile(np.linspace(-1e-4, 2e-4, 5), (nt, 1)))
    return RunState("made_up", np.linspace(0.0, 0.4, nt), theta, 0.3, (beam,))


def test_ribbons_are_as_wide_as_the_section_along_m():
    state = _state()
    quads = animate.ribbon_quads(state, 0, 2)
    assert quads.shape == (4, 4, 3)
    np.testing.assert_allclose(quads[:, 1] - quads[:, 0], np.tile([0.0, 0.1, 0.0], (4, 1)), atol=1e-15)
    np.testing.assert_allclose(0.5 * (quads[:, 0] + quads[:, 1]), state.beams[0].centre_line[2, :-1], atol=1e-15)


def test_the_hub_turns_with_the_hub_angle():
    from hubbeam.io.bodies import rigid_bodies

    state = _state()
    hub = rigid_bodies(state)[0]
    faces = animate.body_faces(hub, 4)
    rim = faces[0]  # the lower cap: a polygon of the hub radius, 1/20 of it below the hub plane
    np.testing.assert_allclose(np.linalg.norm(rim[:, [0, 2]], axis=1), 0.3)
    np.testing.assert_allclose(rim[:, 1], -0.015, atol=1e-15)
    # the hub's first axis (the spoke) lies along the beam's root direction i_h(theta)
    np.testing.assert_allclose(0.3 * hub.rotation[4][:, 0], state.beams[0].centre_line[4, 0], atol=1e-12)


def test_scale_magnifies_the_deflection_from_the_turned_undeformed_beam():
    """A beam bent by d (along j0) drawn with --scale 10 sits at 10 d from the undeformed beam
    turned with the hub, and at 9 d from where it is."""
    from dataclasses import replace

    state = _state()
    beam = state.beams[0]
    bend = np.zeros_like(beam.centre_line)
    bend[:, :, 1] = 0.01 * beam.stations[None, :] ** 2
    state = replace(state, beams=(replace(beam, centre_line=beam.centre_line + bend),))
    plain, scaled = animate.ribbon_quads(state, 0, 3), animate.ribbon_quads(state, 0, 3, scale=10.0)
    np.testing.assert_allclose(scaled - plain, 9.0 * np.stack([bend[3, :-1], bend[3, :-1], bend[3, 1:], bend[3, 1:]],
                                                              axis=1), atol=1e-14)


@pytest.mark.parametrize("view, expected", [("top", (90.0, -90.0)), ("20,45", (20.0, 45.0)), ((10, 5), (10.0, 5.0))])
def test_views_place_the_camera(view, expected):
    assert animate.camera(view) == expected
    fig, _, _ = animate.build(_state(), "none", view=view)
    ax = fig.axes[0]
    assert (ax.elev, ax.azim) == pytest.approx(expected)
    import matplotlib.pyplot as plt

    plt.close(fig)


@pytest.mark.parametrize("view", ["sideways", "1,2,3", "95,0", "nan,0"])
def test_bad_views_are_refused(view):
    with pytest.raises(ValueError, match="view"):
        animate.camera(view)


def test_frames_limits_and_colours():
    state = _state()
    np.testing.assert_array_equal(animate.frame_indices(state, 2), [0, 2, 4])
    fig, update, frames = animate.build(state, "strain", stride=2)
    ax = fig.axes[0]
    limits = [ax.get_xlim(), ax.get_ylim(), ax.get_zlim()]
    spans = [hi - lo for lo, hi in limits]
    assert spans == pytest.approx([spans[0]] * 3)  # equal scales
    for i in frames:  # the limits hold every frame
        update(i)
        assert [ax.get_xlim(), ax.get_ylim(), ax.get_zlim()] == limits
    # the plot's axes are (x, -z, y): the hub axis j0 is up
    np.testing.assert_array_equal(animate._view(np.array([1.0, 2.0, 3.0])), [1.0, -3.0, 2.0])
    import matplotlib.pyplot as plt

    plt.close(fig)
    with pytest.raises(KeyError):
        animate.build(state, "rainbow")


def test_an_interruption_before_the_first_frame_passes_through(tmp_path, monkeypatch):
    """A signal raised while the first frame is drawn must reach the caller as itself: the
    writer's saving() context wrote the frames so far on the way out, and Pillow, with none,
    raised an IndexError that hid the interruption (seen as 'cannot write' under Ctrl-C)."""
    fig, update, frames = animate.build(_state())

    def interrupted(i):
        raise KeyboardInterrupt

    monkeypatch.setattr(animate, "build", lambda *args, **kwargs: (fig, interrupted, frames))
    with pytest.raises(KeyboardInterrupt):
        animate.animate(_state(), tmp_path / "m.gif")
