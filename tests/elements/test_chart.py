"""Chart choice and replacement: the frame and torsion at the nodes survive a remap."""

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import choose_director, frame_from_director, remap_chart
from hubbeam.system.beam import AncfBeam
from tests.conftest import plate
from tests.elements.test_gauss_order import helix_state


def test_director_for_a_planar_circle_is_its_normal():
    s = np.linspace(0, 2 * np.pi, 50)
    t = np.column_stack([np.cos(s), np.sin(s), 0 * s])
    d = choose_director(t)
    assert abs(abs(d[2]) - 1) < 1e-9


def test_director_for_a_bundle_is_near_its_mean():
    t = np.array([[1, 0.1, 0], [1, -0.1, 0.05], [1, 0, -0.1]], float)
    assert np.min(t / np.linalg.norm(t, axis=1, keepdims=True) @ choose_director(t)) > 0.99


@pytest.mark.parametrize("new_director", [[0, 1, 0], [-0.3, 0.2, 0.9], [0, 0, 1]])
def test_remap_keeps_nodal_frames_and_torsion(new_director):
    beam = AncfBeam(1.45, 6, plate())
    q, F = helix_state(beam, turns=0.3)
    F_new = frame_from_director(np.array(new_director, float))
    nodes = remap_chart(q.reshape(beam.nodes, 8), beam.node_tangent_rates(q), F, F_new)
    q_new = nodes.ravel()
    for k in range(beam.nodes):
        x = min(k * beam.element_length, beam.length)
        assert np.allclose(beam.frame_at(q, F, x), beam.frame_at(q_new, F_new, x), atol=1e-12)
    # strain energy is nearly unchanged (exact for straight elements; interpolation error otherwise)
    U0 = beam.elastic(q, F, tangent=False)[0]
    U1 = beam.elastic(q_new, F_new, tangent=False)[0]
    assert abs(U1 - U0) < 1e-3 * U0


def test_remap_of_a_straight_beam_is_exact():
    beam = AncfBeam(1.45, 4, plate())
    q, F = beam.straight_state(np.zeros(3), frame_from_director(np.array([0.6, 0.8, 0.0])))
    F_new = frame_from_director(np.array([0.0, 0.0, 1.0]))
    q_new = remap_chart(q.reshape(beam.nodes, 8), beam.node_tangent_rates(q), F, F_new).ravel()
    for x in np.linspace(0, beam.length, 13):
        assert np.allclose(beam.frame_at(q, F, x), beam.frame_at(q_new, F_new, x), atol=1e-12)
