"""The ANCF mesh's assembled operations."""

import numpy as np

from hubbeam.system.assembly import add_element_blocks_dense
from hubbeam.system.beam import AncfBeam
from tests.conftest import L, plate


def test_apply_mass_equals_the_assembled_matrix_times_the_vector():
    beam = AncfBeam(L, 5, plate())
    rng = np.random.default_rng(4)
    q, _ = beam.straight_state(np.zeros(3), np.eye(3))
    q = q + 1e-2 * rng.standard_normal(q.size)
    F = np.eye(3)
    blocks = beam.mass_blocks(q, F)
    M = np.zeros((beam.ndof, beam.ndof))
    add_element_blocks_dense(M, blocks, 0, 1.0)
    u = rng.standard_normal(beam.ndof)
    assert np.allclose(beam.apply_mass(blocks, u), M @ u, rtol=1e-13, atol=1e-15)
