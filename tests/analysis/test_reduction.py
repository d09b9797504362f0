"""Reduced linear models against what they must keep: on a model whose modes are known by
construction, the kept poles, residues and the residualised DC gain by hand; balanced
reduction's Hankel singular values against the Gramians solved another way, and its
H-infinity bound; on the bundled spacecraft (a PD-controlled bus with two panels), the DC
gain of hub torque to hub angle 1/kp and the lowest poles of the full model."""

import numpy as np
import pytest
import scipy.linalg

from hubbeam import api
from hubbeam.analysis import reduction
from hubbeam.errors import ScenarioError
from hubbeam.io.scenario import load_example


def modal_plant(omegas, zetas, b, c, seed=0):
    """G(s) = sum_i c_i b_i / (s^2 + 2 zeta_i omega_i s + omega_i^2) (one input, one output):
    second-order modes (position, velocity) hidden by a random similarity transform."""
    n = len(omegas)
    A = scipy.linalg.block_diag(*[np.array([[0.0, 1.0], [-w**2, -2 * z * w]]) for w, z in zip(omegas, zetas)])
    B = np.concatenate([[0.0, bi] for bi in b])[:, None]
    C = np.concatenate([[ci, 0.0] for ci in c])[None, :]
    rng = np.random.default_rng(seed)
    T = np.linalg.qr(rng.standard_normal((2 * n, 2 * n)))[0] * rng.uniform(1.0, 2.0, 2 * n)  # condition <= 2
    Ti = np.linalg.inv(T)
    return Ti @ A @ T, Ti @ B, C @ T, np.zeros((1, 1))


def transfer(A, B, C, D, s):
    return (C @ np.linalg.solve(s * np.eye(A.shape[0]) - A, B) + D)[0, 0]


OMEGAS, ZETAS = [2.0, 9.0, 40.0, 150.0], [0.02, 0.05, 0.01, 0.03]
B_IN, C_OUT = [1.0, 0.7, -0.4, 0.9], [1.0, -0.5, 0.8, 0.3]


def test_modal_truncation_keeps_the_lowest_modes_exactly_and_residualises_the_rest_by_hand():
    A, B, C, D = modal_plant(OMEGAS, ZETAS, B_IN, C_OUT)
    red = reduction.modal_reduction(A, B, C, D, count=2)
    assert red.states == ["mode1_re", "mode1_im", "mode2_re", "mode2_im"]
    kept = np.sort_complex(np.linalg.eigvals(red.A))
    exact = np.sort_complex(np.concatenate([[-z * w + 1j * w * np.sqrt(1 - z * z), -z * w - 1j * w * np.sqrt(1 - z * z)]
                                            for w, z in zip(OMEGAS[:2], ZETAS[:2])]))
    np.testing.assert_allclose(kept, exact, rtol=1e-12)
    # by hand: the dropped modes add their static gain c b / omega^2, the kept ones stay whole
    dropped = sum(c * b / w**2 for w, b, c in zip(OMEGAS[2:], B_IN[2:], C_OUT[2:]))
    np.testing.assert_allclose(red.D[0, 0], dropped, rtol=1e-10)
    for s in (0.0, 1j, 3j, 0.5 + 20j):
        by_hand = sum(c * b / (s * s + 2 * z * w * s + w * w) for w, z, b, c in
                      zip(OMEGAS[:2], ZETAS[:2], B_IN[:2], C_OUT[:2])) + dropped
        np.testing.assert_allclose(transfer(red.A, red.B, red.C, red.D, s), by_hand, rtol=1e-10)
    # real block form: each complex pair a [[sigma, omega], [-omega, sigma]] block
    sigma, omega = red.A[0, 0], red.A[0, 1]
    np.testing.assert_allclose(red.A[:2, :2], [[sigma, omega], [-omega, sigma]], atol=1e-12 * abs(omega))
    assert np.all(red.A[:2, 2:] == 0) and np.all(red.A[2:, :2] == 0)


def test_fmax_drops_the_modes_above_it_and_a_rigid_mode_is_kept_as_it_is():
    A, B, C, D = modal_plant(OMEGAS, ZETAS, B_IN, C_OUT)
    red = reduction.modal_reduction(A, B, C, D, fmax=10 / (2 * np.pi))  # between 9 and 40 rad/s
    assert red.info["kept_modes"] == 2 and red.info["residualised_modes"] == 2
    # a free rigid body in front: x'' = u (a double zero eigenvalue, a Jordan block)
    Ar = scipy.linalg.block_diag(np.array([[0.0, 1.0], [0.0, 0.0]]), A)
    Br, Cr = np.vstack([[[0.0], [1.0]], B]), np.hstack([[[1.0, 0.0]], C])
    red = reduction.modal_reduction(Ar, Br, Cr, D, count=1, rigid_modes=1)
    assert red.states[:2] == ["rigid1", "rigid2"] and red.A.shape == (4, 4)
    for s in (0.7j, 2j):  # the rigid part 1/s^2 kept exactly
        full = transfer(Ar, Br, Cr, D, s) - transfer(A, B, C, D, s)
        np.testing.assert_allclose(full, 1 / s**2, rtol=1e-10)


def test_hankel_singular_values_are_those_of_the_gramians_solved_by_kronecker_products():
    A, B, C, D = modal_plant(OMEGAS, ZETAS, B_IN, C_OUT, seed=3)
    n = A.shape[0]
    eye = np.eye(n)
    P = np.linalg.solve(np.kron(eye, A) + np.kron(A, eye), -(B @ B.T).ravel(order="F")).reshape(n, n, order="F")
    Q = np.linalg.solve(np.kron(eye, A.T) + np.kron(A.T, eye), -(C.T @ C).ravel(order="F")).reshape(n, n, order="F")
    expected = np.sort(np.sqrt(np.abs(np.linalg.eigvals(P @ Q))))[::-1]
    sigma = reduction.hankel_singular_values(A, B, C)[0]
    np.testing.assert_allclose(sigma, expected, rtol=1e-7, atol=1e-9 * sigma[0])


@pytest.mark.parametrize("match", ["dc", "truncate"])
@pytest.mark.parametrize("order", [2, 4, 6])
def test_balanced_error_is_within_twice_the_discarded_hankel_singular_values(order, match):
    A, B, C, D = modal_plant(OMEGAS, ZETAS, B_IN, C_OUT, seed=1)
    red = reduction.balanced_reduction(A, B, C, D, order, match=match)
    sigma = np.array(red.info["hankel_singular_values"])
    bound = 2 * np.sum(sigma[order:])
    assert red.A.shape == (order, order) and red.info["error_bound"] == pytest.approx(bound)
    w = np.unique(np.concatenate([np.logspace(-2, 3.5, 4000), OMEGAS]))
    error = max(abs(transfer(A, B, C, D, 1j * x) - transfer(red.A, red.B, red.C, red.D, 1j * x)) for x in w)
    assert error <= bound * (1 + 1e-9)
    assert error > 0.05 * bound  # the bound is not loose by orders of magnitude here
    if match == "dc":  # residualised: the DC gain kept
        np.testing.assert_allclose(transfer(red.A, red.B, red.C, red.D, 0.0), transfer(A, B, C, D, 0.0), rtol=1e-9)
    else:  # truncated: exact at infinite frequency
        np.testing.assert_allclose(red.D, D)
    assert np.all(np.linalg.eigvals(red.A).real < 0)


def test_frequency_response_is_the_dense_solve():
    A, B, C, D = modal_plant(OMEGAS, ZETAS, B_IN, C_OUT)
    f = [0.0, 0.3, 1.4321, 25.0]
    G = reduction.frequency_response(A, B, C, D, f)
    np.testing.assert_allclose(G[:, 0, 0], [transfer(A, B, C, D, 2j * np.pi * x) for x in f], rtol=1e-11)


# ---------------------------------------------------------------- the bundled spacecraft
@pytest.fixture(scope="module")
def spacecraft():
    """The bundled spacecraft (PD law kp = 20 N m/rad, no damping but kd's): hub torque to the
    hub angle, a panel tip and a root strain."""
    return api.linearize(load_example("spacecraft"), outputs=["theta", "tip_a_tangential", "root_strain_a"])


def test_modal_dc_gain_is_one_over_kp_and_the_kept_poles_are_the_full_models(spacecraft):
    full = spacecraft
    model = full.reduced(3)
    assert model.A.shape == (6, 6) and model.reduction["full_states"] == full.A.shape[0]
    # a constant torque turns the bus by u / kp, rigidly: no tip deflection, no strain
    np.testing.assert_allclose(model.dc_gain()[:, 0], [1 / 20.0, 0.0, 0.0], atol=1e-6 / 20.0)
    np.testing.assert_allclose(model.dc_gain(), full.dc_gain(), atol=1e-6 / 20.0)
    # the kept poles are the full model's (scipy's eigenvalues of A: another solver)
    s_full = scipy.linalg.eigvals(full.A)
    for s in model.eigenvalues():
        assert np.min(np.abs(s_full - s)) <= 1e-6 * abs(s)
    # ... its three lowest modes that the torque reaches (the symmetric panel modes leave the
    # bus still: PD's kd cannot damp them, no torque excites them)
    f, zeta = full.modal_summary()
    reached = f[np.abs(zeta) > 1e-10][:3]
    np.testing.assert_allclose(np.sort(model.modal_summary()[0]), reached, rtol=1e-6)
    assert np.all(np.abs(zeta[np.abs(zeta) <= 1e-10]) < 1e-10) and model.reduction["invisible_modes"] > 0


def test_balanced_spacecraft_within_its_bound_with_the_dc_gain_kept(spacecraft):
    model = spacecraft.balanced(4)
    bound = model.reduction["error_bound"]
    sigma = model.to_dict()["hankel_singular_values"]
    assert bound == pytest.approx(2 * sum(sigma[4:]))
    f = np.unique(np.concatenate([np.logspace(-3, 4, 1500), np.abs(spacecraft.eigenvalues()) / (2 * np.pi)]))
    f = f[f < 3e4]
    error = np.max(np.linalg.norm(spacecraft.frequency_response(f) - model.frequency_response(f), axis=(1, 2)))
    assert error <= bound
    np.testing.assert_allclose(model.dc_gain(), spacecraft.dc_gain(), atol=1e-6 / 20.0)


def test_reduction_options_through_the_api_are_checked():
    sc = load_example("spacecraft")
    with pytest.raises(ScenarioError, match="reduce"):
        api.linearize(sc, reduce=2, balanced=2)
    with pytest.raises(ScenarioError, match="reduce: a whole number"):
        api.linearize(sc, reduce=0)
    with pytest.raises(ScenarioError, match="fmax"):
        api.linearize(sc, fmax=-1.0)
    with pytest.raises(ScenarioError, match="outputs: unknown 'nope'"):
        api.linearize(sc, outputs=["nope"])
    held = load_example("cantilever", ["beam.elements=2", "damping.linear=0", "damping.quadratic=0"])
    with pytest.raises(ScenarioError, match="no stable part"):
        api.linearize(held, balanced=2)
