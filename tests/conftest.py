"""Shared fixtures: the reference plate of conventions.md and small helpers."""

import numpy as np
import pytest

from hubbeam.elements.section import Section, saint_venant_torsion_constant

B, H, E, NU, RHO, L = 0.05, 0.0025, 70e9, 0.33, 2700.0, 1.45


def plate(width=B, thickness=H) -> Section:
    return Section(width, thickness, RHO, E, E / (2 * (1 + NU)), saint_venant_torsion_constant(width, thickness))


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

    state = initial_state(system)
    p = ga.AlphaParameters.from_spectral_radius(0.8)
    options = ga.NewtonOptions(update=update)
    fast, slow = CompiledSteps(system, p, options, dt, state), PythonSteps(system, p, options, dt, state)
    a, steps_a, its_a, _, err_a, rec_a = fast.advance(state, steps, 0, every, steps)
    b, steps_b, its_b, _, err_b, rec_b = slow.advance(state, steps, 0, every, steps)
    assert err_a is None and err_b is None and steps_a == steps_b == steps
    assert its_a == its_b  # the same Newton iterations, step by step
    times = [dt * k for k in range(every, steps + 1, every)]
    assert [r[0].t for r in rec_a] == [r[0].t for r in rec_b] == pytest.approx(times)
    for u, w in ((a.x, b.x), (a.v, b.v), (a.xdd, b.xdd), (a.a, b.a), (a.lam, b.lam)):
        assert np.max(np.abs(u - w)) <= 1e-9 * max(1.0, np.max(np.abs(w)))
    assert fast.work["dissipated"] == pytest.approx(slow.work["dissipated"], rel=1e-9)
    assert fast.work["drive"] == pytest.approx(slow.work["drive"], rel=1e-9)
    return a, b, fast, slow
