"""Shared fixtures: the reference plate of conventions.md and small helpers."""

import numpy as np
import pytest

from hubbeam.elements.section import Section, saint_venant_torsion_constant

B, H, E, NU, RHO, L = 0.05, 0.0025, 70e9, 0.33, 2700.0, 1.45


def plate(width=B, thickness=H) -> Section:
    return Section(width, thickness, RHO, E, E / (2 * (1 + NU)), saint_venant_torsion_constant(width, thickness))


def tapered_sections(length=L, root=(B, H), tip=(0.6 * B, 0.6 * H), pretwist_deg=60.0, material=None):
    """A linearly tapered rectangle (width, thickness from ``root`` to ``tip``) of the plate's material,
    pretwisted linearly to ``pretwist_deg`` at the tip."""
    from hubbeam.elements.section import SectionForm, SpanSections

    return SpanSections(np.array([0.0, length]), SectionForm.RECTANGLE, np.array([root, tip], dtype=float),
                        np.radians([0.0, pretwist_deg]), material or plate())


@pytest.fixture
def section() -> Section:
    return plate()


def rotation(axis, angle) -> np.ndarray:
    """Rodrigues rotation matrix (independent of the code's frame construction)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def central_difference(fun, x, h):
    """Column-wise central difference of a vector function."""
    x = np.asarray(x, float)
    cols = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h
        cols.append((np.asarray(fun(x + e)) - np.asarray(fun(x - e))) / (2 * h))
    return np.array(cols).T


def assert_compiled_steps_are_python_steps(system, update, dt=2e-3, steps=40, every=10):
    """Take the same steps with the compiled loop and the Python step from the system's start
    state: the same Newton iterations, records, states (to 1e-9) and work integrals. Returns
    the two final states (compiled, Python) and the two steppers."""
    from hubbeam.simulation import CompiledSteps, PythonSteps, initial_state
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers import newton_control as nc

    state = initial_state(system)
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    options = nc.NewtonOptions(update=update)
    fast, slow = CompiledSteps(system, p, options, dt, state), PythonSteps(system, p, options, dt, state)
    a, steps_a, its_a, _, err_a, rec_a = fast.advance(state, steps, 0, every, steps)
    b, steps_b, its_b, _, err_b, rec_b = slow.advance(state, steps, 0, every, steps)
    assert err_a is None and err_b is None and steps_a == steps_b == steps
    assert its_a == its_b  # the same Newton iterations, step by step
    times = [dt * k for k in range(every, steps + 1, every)]
    assert rec_a.states.t.tolist() == rec_b.states.t.tolist() == pytest.approx(times)
    for u, w in ((rec_a.states.x, rec_b.states.x), (rec_a.states.v, rec_b.states.v),  # the records: states, work
                 (rec_a.dissipated, rec_b.dissipated), (rec_a.drive, rec_b.drive)):
        assert np.max(np.abs(u - w)) <= 1e-9 * max(1.0, np.max(np.abs(w)))
    for u, w in ((a.x, b.x), (a.v, b.v), (a.xdd, b.xdd), (a.a, b.a), (a.lam, b.lam)):
        assert u.shape == w.shape and (w.size == 0 or np.max(np.abs(u - w)) <= 1e-9 * max(1.0, np.max(np.abs(w))))
    assert fast.work["dissipated"] == pytest.approx(slow.work["dissipated"], rel=1e-9)
    assert fast.work["drive"] == pytest.approx(slow.work["drive"], rel=1e-9)
    return a, b, fast, slow


#: beta h^2, gamma', beta' of generalized-alpha at h = 1 ms (rho_inf about 0.8)
ALPHA_COEFS = (0.3e-6, 1.1e3, 3.3e6)


def newton_matrix_and_differences(system, seed=3, perturbation=0.02, stiffness="dynamic", theta=0.3, t=0.3):
    """A system's Newton matrix at a perturbed state at rest and the central differences of its
    residual along the generalized-alpha correction (z moves x by dz, v by gamma' dz, xdd by
    beta' dz, lambda by s/ck dmu). Returns (matrix, differences, residual, residual of the
    difference function at z = 0), dense, on z."""
    ck, gp, bp = ALPHA_COEFS
    s = system.mass_scale
    x0, F = system.initial_state(theta)
    rng = np.random.default_rng(seed)
    x0[1:] += perturbation * rng.normal(size=x0.size - 1)
    layout = system.layout
    lam0 = rng.normal(size=layout.n_lambda)
    zero = np.zeros_like(x0)

    def residual(z):
        dx, dmu = layout.split_z(z)
        return system.equations(x0 + dx, gp * dx, bp * dx, lam0 + s / ck * dmu, F, t, 0.0, 0.0, ck, s,
                                want_matrix=False)[0]

    res, matrix = system.equations(x0, zero, zero, lam0, F, t, ck * bp, ck * gp, ck, s, stiffness=stiffness)
    A = matrix.to_dense()
    return A, central_difference(residual, np.zeros(A.shape[0]), 1e-7), res, residual(np.zeros(A.shape[0]))
