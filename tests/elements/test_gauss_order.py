"""The Gauss order of the strain energy: the convergence study behind DEFAULT_GAUSS_POINTS.

State: a stretched helix (0.6 turn over the beam, pitch 0.3) with a quadratic twist,
sampled exactly at the nodes. Relative error of U against 10 points, 4 elements:
order 3: 2e-4, 4: 2e-4, 5: 8e-8, 6: 8e-8, 7: 4e-11 (odd orders include the midpoint).
"""

import numpy as np

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.system.beam import DEFAULT_GAUSS_POINTS, AncfBeam
from tests.conftest import plate


def helix_state(beam, turns=0.6, pitch=0.3, stretch=1.001, twist=1.5):
    rho = beam.length / (2 * np.pi * turns)
    c, a = pitch / np.sqrt(1 + pitch**2), 1 / np.sqrt(1 + pitch**2)
    q = np.zeros(beam.ndof)
    for k in range(beam.nodes):
        s = k * beam.element_length
        q[8 * k : 8 * k + 3] = stretch * np.array([a * rho * np.sin(s / rho), a * rho * (1 - np.cos(s / rho)), c * s])
        q[8 * k + 3 : 8 * k + 6] = stretch * np.array([a * np.cos(s / rho), a * np.sin(s / rho), c])
        q[8 * k + 6], q[8 * k + 7] = twist * s**2, 2 * twist * s
    return q, frame_from_director(np.array([0.0, 0.0, 1.0]))


def relative_errors(elements):
    energies = {}
    for order in range(2, 11):
        beam = AncfBeam(1.45, elements, plate(), gauss_points=order)
        q, F = helix_state(beam)
        energies[order] = beam.elastic(q, F, tangent=False)[0]
    return {k: abs(v - energies[10]) / energies[10] for k, v in energies.items() if k < 10}


def test_default_gauss_order_has_converged_strain_energy():
    err = relative_errors(4)
    assert err[DEFAULT_GAUSS_POINTS] < 1e-6
    assert err[3] > 1e-5  # three points are visibly not enough
    assert err[7] < err[5] < err[3]


def test_quadrature_error_falls_with_mesh_refinement():
    assert relative_errors(8)[DEFAULT_GAUSS_POINTS] < relative_errors(4)[DEFAULT_GAUSS_POINTS] / 10
