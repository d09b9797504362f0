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


def test_setup_terms_in_numpy_equal_the_compiled_kernels_bitwise():
    """AncfBeam computes its translational mass blocks and its distributed loads (gravity) in
    numpy at start-up (no compiled-function load); they are the kernels' sums term for term."""
    from hubbeam.elements.ancf import kernels
    from hubbeam.elements.hermite import gauss_legendre, hermite
    from hubbeam.system.beam import distributed_load, translational_mass_blocks

    rng = np.random.default_rng(13)
    for n_el, ng in ((1, 2), (5, 5), (8, 4)):
        xi, w = gauss_legendre(ng)
        length = L / n_el
        S = np.ascontiguousarray(hermite(xi, length)[0])
        rho_a = 6.0 + rng.random((n_el, ng))  # a different rho A at every Gauss point (a tapered beam)
        blocks = translational_mass_blocks(length, S, w, rho_a)
        assert blocks.shape == (n_el, 16, 16)
        for el in range(n_el):
            assert np.array_equal(blocks[el], kernels.translational_mass_block(length, S, w, rho_a[el]))
        load = rng.standard_normal(3)
        expected = np.empty(8 * (n_el + 1))
        kernels.distributed_load(n_el, length, S, w, rho_a, load, expected)
        assert np.array_equal(distributed_load(n_el, length, S, w, rho_a, load), expected)
