"""The column update of a kept Newton matrix (solvers/column_update.py): the patched factors
solve the patched matrix (and the drifted patch its extrapolation), the controller asks for
patches and backs off from them, and a beam
on a hinge integrated with patches takes the Python step's steps and ends where the run that
refactorises ends, to the Newton tolerance."""

import numpy as np
import pytest

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.simulation import CompiledSteps, initial_state
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.solvers.column_update import PatchedMatrix, joint_columns
from hubbeam.system.assembly import BorderedBandMatrix
from tests.conftest import assert_compiled_steps_are_python_steps


def _random_bordered(n=14, border=2, bandwidth=3, seed=1):
    """A random bordered band matrix (diagonally dominant) and its dense copy."""
    rng = np.random.default_rng(seed)
    m = BorderedBandMatrix.empty(n, border, bandwidth)
    for i in range(n):
        for j in range(n):
            if i < border or j < border or abs(i - j) <= bandwidth:
                m.add(i, j, rng.normal() + (4.0 if i == j else 0.0))
    return m, m.to_dense()


def _patched_dense(A, C, columns):
    """A with its columns J replaced by C and its rows J changed by the transpose of the columns'
    change (the J x J block once), written out densely."""
    E = np.eye(A.shape[0])[:, columns]
    U = C - A[:, columns]
    Ut = U.copy()
    Ut[columns, :] = 0.0
    return A + U @ E.T + E @ Ut.T


@pytest.mark.parametrize("columns", [[5], [1, 6, 11]])
def test_the_patched_factors_solve_the_patched_matrix_to_rounding(columns):
    """Columns (one in the border, one in the band's last columns) replaced by random ones: the
    Woodbury solve on the old factors equals numpy's dense solve of the patched matrix."""
    m, A = _random_bordered()
    rng = np.random.default_rng(2)
    C = rng.normal(size=(A.shape[0], len(columns))) + 3.0 * np.eye(A.shape[0])[:, columns]
    z = np.array(columns, dtype=np.int64)
    base = ga.factorise(m, 1e-3, None, z)
    assert np.array_equal(base.columns, A[:, columns].T)  # the kept columns, read from the band storage
    patched = PatchedMatrix(base, C, z)
    new = _patched_dense(A, C, columns)
    assert np.max(np.abs(new[:, columns] - C)) < 1e-14 * np.max(np.abs(C))
    b = rng.normal(size=A.shape[0])
    exact = np.linalg.solve(new, b)
    assert np.max(np.abs(patched.solve(b) - exact)) < 1e-12 * np.max(np.abs(exact))
    # a second patch changes the factorised matrix, not the first patch: back to A itself
    again = PatchedMatrix(patched.base, A[:, columns], z)
    assert np.max(np.abs(again.solve(b) - np.linalg.solve(A, b))) < 1e-12 * np.max(np.abs(np.linalg.solve(A, b)))


def test_a_drifted_patch_solves_the_linearly_extrapolated_patched_matrix():
    """Two patches of the same factors 3 steps apart, the second carried 2 steps on: its
    Woodbury solve equals numpy's dense solve of A patched with C1 + 2 (C1 - C0) / 3."""
    m, A = _random_bordered()
    rng = np.random.default_rng(5)
    columns = [1, 6]
    z = np.array(columns, dtype=np.int64)
    C0 = A[:, columns] + 0.3 * rng.normal(size=(A.shape[0], 2))
    C1 = C0 + 0.1 * rng.normal(size=C0.shape)
    base = ga.factorise(m, 1e-3, None, z)
    first = PatchedMatrix(base, C0, z)
    second = PatchedMatrix(base, C1, z)
    G0, Ut0 = first.G.copy(), first.Ut.copy()
    second.follow(first, 3)
    # the earlier patch is left as it was (follow once wrote the new patch into its G_last / Ut_last)
    assert np.array_equal(first.G_last, G0) and np.array_equal(first.Ut_last, Ut0)
    b = rng.normal(size=A.shape[0])
    assert np.max(np.abs(second.solve(b) - np.linalg.solve(_patched_dense(A, C1, columns), b))) < 1e-12 * 10
    second.drift(2)
    exact = np.linalg.solve(_patched_dense(A, C1 + 2.0 * (C1 - C0) / 3.0, columns), b)
    assert np.max(np.abs(second.solve(b) - exact)) < 1e-12 * np.max(np.abs(exact))
    second.drift(0)  # back at the patch itself
    assert np.max(np.abs(second.solve(b) - np.linalg.solve(_patched_dense(A, C1, columns), b))) < 1e-11


def test_a_patch_drifts_only_after_a_second_patch_of_the_same_factors():
    reuse = nc.reuse_state()
    nc.factorised(reuse)
    assert not nc.patch_drifts(reuse, True)  # no patch yet
    reuse[nc.REUSE_PATCH] = 1
    assert not nc.patch_drifts(reuse, True)
    assert nc.patch_made(reuse) == 0  # the first patch of these factors: nothing to drift from
    reuse[nc.REUSE_PATCH] = 0
    assert not nc.patch_drifts(reuse, True) and not nc.patch_drifts(reuse, True)
    reuse[nc.REUSE_PATCH] = 1
    assert not nc.patch_drifts(reuse, True)  # the step that makes the next patch
    assert nc.patch_made(reuse) == 3  # three steps after the first
    reuse[nc.REUSE_PATCH] = 0
    assert nc.patch_drifts(reuse, True) and reuse[nc.REUSE_PATCH_AGE] == 1
    assert not nc.patch_drifts(reuse, False)  # a step with a new matrix
    nc.factorised(reuse)
    assert not nc.patch_drifts(reuse, True) and reuse[nc.REUSE_DRIFT_STEPS] == 0


def test_a_singular_patched_matrix_is_refused():
    m, A = _random_bordered()
    z = np.array([4], dtype=np.int64)
    with pytest.raises(np.linalg.LinAlgError):
        PatchedMatrix(ga.factorise(m, 1e-3, None, z), np.zeros((A.shape[0], 1)), z)


def _decide(reuse, it, stale, columns, patched):
    """newton_decide after a converging increment (size 0) at iteration ``it``."""
    return nc.newton_decide(0.0, np.inf, it, stale, int(nc.MatrixUpdate.ADAPTIVE), 0.25, 2, 0, 1e-9, reuse,
                            nc.borrowed_rate(), nc.KAPPA, columns, patched)


def test_the_controller_patches_a_stale_matrix_and_backs_off_when_patches_fail():
    reuse = nc.reuse_state()
    reuse[nc.REUSE_VALID] = 1
    _decide(reuse, 3, True, 0, False)  # no joint columns: refactorise, as always
    assert reuse[nc.REUSE_VALID] == 0 and reuse[nc.REUSE_PATCH] == 0
    reuse[nc.REUSE_VALID] = 1
    _decide(reuse, 3, True, 1, False)  # a kept matrix went stale: patch it at the next step
    assert reuse[nc.REUSE_VALID] == 1 and reuse[nc.REUSE_PATCH] == 1
    reuse[nc.REUSE_PATCH] = 0
    _decide(reuse, 3, True, 1, True)  # the patch did not help: refactorise, then the next stale one too
    assert reuse[nc.REUSE_VALID] == 0 and reuse[nc.REUSE_PATCH_WAIT] == 1 and reuse[nc.REUSE_PATCH_BACKOFF] == 2
    reuse[nc.REUSE_VALID] = 1
    _decide(reuse, 3, True, 1, False)
    assert reuse[nc.REUSE_VALID] == 0 and reuse[nc.REUSE_PATCH_WAIT] == 0
    reuse[nc.REUSE_VALID] = 1
    _decide(reuse, 3, True, 1, False)  # the wait is over
    assert reuse[nc.REUSE_VALID] == 1 and reuse[nc.REUSE_PATCH] == 1
    _decide(reuse, 2, True, 1, True)  # a patch that worked resets the back-off
    assert reuse[nc.REUSE_VALID] == 1 and reuse[nc.REUSE_PATCH_BACKOFF] == 1
    _decide(reuse, 3, False, 1, False)  # a matrix made in this step is not patched
    assert reuse[nc.REUSE_VALID] == 0


def _exp1_on_a_hinge(modes, joint='{kind="revolute", axis="flap", stiffness=1.0e4}'):
    """exp1 (the FFR plate, free hub, released under gravity) on the stiff flap hinge of case J
    (or on ``joint``)."""
    extra = ['beam.formulation="ffr"', f"beam.joint={joint}"]
    return api.build_system(load_example("exp1", extra + ([f"beam.modes={modes}"] if modes else [])))


def test_the_compiled_loop_patches_as_the_python_step_does(monkeypatch):
    """The same steps, iterations and states (conftest's check) over a run in which the kept
    matrix is patched and the patches drift, and both happened."""
    drifts = []
    drift = PatchedMatrix.drift
    monkeypatch.setattr(PatchedMatrix, "drift", lambda self, age: drifts.append(age) or drift(self, age))
    _, _, fast, _ = assert_compiled_steps_are_python_steps(_exp1_on_a_hinge(4), "adaptive", dt=1e-3, steps=200,
                                                           every=50)
    assert fast.patches >= 3 and len(drifts) >= 3


@pytest.mark.slow
def test_the_compiled_loop_patches_two_joint_columns_as_the_python_step_does(monkeypatch):
    """As above on a flap and lag joint (two joint angles: a patch of two columns and two rows,
    a 4 x 4 capacitance, and their drift): the same steps, iterations and states, and patches
    and drifts both happened."""
    drifts = []
    drift = PatchedMatrix.drift
    monkeypatch.setattr(PatchedMatrix, "drift", lambda self, age: drifts.append(age) or drift(self, age))
    system = _exp1_on_a_hinge(4, '{kind="revolute", axis=["flap", "lag"], stiffness=[1.0e4, 1.0e4]}')
    assert joint_columns(system.layout).tolist() == [1, 2]  # theta, then the flap and lag angles
    _, _, fast, _ = assert_compiled_steps_are_python_steps(system, "adaptive", dt=1e-3, steps=300, every=50)
    assert fast.patches >= 3 and len(drifts) >= 3


@pytest.mark.parametrize("modes", [0, 4])
def test_patches_end_where_refactorising_ends(modes):
    """2 s with and without the column update: the patched run factorises far less and its
    states stay within 1e-7 m (rad) of the other's (both converge each step to 1e-9 L with
    kappa = 0.01; their difference, the two runs' different Newton errors carried by the lightly
    damped beam, measured 3e-8 to 1e-7 over 10 s: benchmarks/joint_cost.py columns)."""
    system = _exp1_on_a_hinge(modes)
    assert joint_columns(system.layout).tolist() == [1]  # theta, then the hinge's psi
    state, p = initial_state(system), ga.AlphaParameters.from_spectral_radius(0.8)
    runs = []
    for update in (True, False):
        loop = CompiledSteps(system, p, nc.NewtonOptions(update_columns=update), 1e-3, state)
        _, n, its, _, err, chunk = loop.advance(state, 2000, 0, 20, 2000)
        assert err is None
        runs.append((loop, chunk.states.x, its / n))
    (patched, x1, newton), (refactorised, x0, _) = runs
    assert patched.patches > 0 and refactorised.patches == 0
    assert patched.factorisations < 0.2 * refactorised.factorisations
    # drifting patches: 2.089 (4 modes) and 2.061 (nodal) iterations and 0.084 and 0.057 patches per
    # step; patches that do not drift: 2.276 and 2.190, 0.27 and 0.18 (the step after each patch took
    # a third iteration)
    assert newton < 2.15 and patched.patches < 0.12 * n
    assert np.max(np.abs(x1 - x0)) < 1e-7
