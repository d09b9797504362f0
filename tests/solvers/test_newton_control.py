"""The Newton controller's decisions on a kept matrix: the first-iteration test with a
contraction rate borrowed from earlier steps (NewtonOptions.borrowed_rate_steps), called as the
step and the compiled loop call it; the runs with it are in test_generalized_alpha.py."""

import numpy as np

from hubbeam.solvers import newton_control as nc

ADAPTIVE = int(nc.MatrixUpdate.ADAPTIVE)
TOL = 1e-9


def _newton_step(reuse, rate, first, second=None, borrowed_steps=8):
    """One step's controller calls on the kept matrix: the first increment ``first``, then (if it
    does not converge) the second ``second``. Returns the iterations the step took."""
    assert nc.newton_start(ADAPTIVE, reuse)
    action = nc.newton_decide(first, np.inf, 1, True, ADAPTIVE, 0.25, 2, borrowed_steps, TOL, reuse, rate, nc.KAPPA,
                              0, False)
    if action == nc.NewtonAction.CONVERGED:
        return 1
    assert action == nc.NewtonAction.KEEP
    assert nc.newton_decide(second, first, 2, True, ADAPTIVE, 0.25, 2, borrowed_steps, TOL, reuse, rate, nc.KAPPA, 0,
                            False) == nc.NewtonAction.CONVERGED
    return 2


def test_the_borrowed_rate_is_dropped_when_the_matrix_is_refactorised_or_patched():
    """Two steps measure the kept matrix's rate (1e-4), the third stops after its first increment
    (1e-8 m: 1e-8 * 3e-4 / 0.01 < 1e-9); after a factorisation or a patch the same increment
    iterates twice again (a rate kept across them would let it stop)."""
    for renew in (nc.factorised, nc.patch_made):
        reuse, rate = nc.reuse_state(), nc.borrowed_rate()
        nc.factorised(reuse)
        assert [_newton_step(reuse, rate, 1e-6, 1e-10) for _ in range(3)] == [2, 2, 2]  # no rate, one rate, then:
        assert _newton_step(reuse, rate, 1e-8, 1e-12) == 1
        renew(reuse)
        assert _newton_step(reuse, rate, 1e-8, 1e-12) == 2


def test_the_borrowed_rate_is_the_larger_of_two_times_the_age_and_is_measured_again_after_m_steps():
    reuse, rate = nc.reuse_state(), nc.borrowed_rate()
    nc.factorised(reuse)
    _newton_step(reuse, rate, 1e-6, 1e-10)  # 1e-4 at age 1
    _newton_step(reuse, rate, 1e-6, 1e-13)  # 1e-7 at age 2
    # age 3: 3e-4, the larger of the two per step of age, allows 1e-8 m but not 1e-7 m (1e-7 would pass with 1e-7)
    assert _newton_step(reuse, rate, 1e-7, 1e-12, borrowed_steps=2) == 2  # measures 1e-5 (per age 3.3e-6)
    assert [_newton_step(reuse, rate, 1e-8, 1e-12, borrowed_steps=2) for _ in range(4)] == [1, 1, 2, 1]
    reuse[nc.REUSE_AGE] = 1000  # the same rates 1000 steps after the factorisation: 0.017 leaves 1.7e-10 m, too much
    assert _newton_step(reuse, rate, 1e-8, 1e-12) == 2
    reuse, rate = nc.reuse_state(), nc.borrowed_rate()  # borrowed_rate_steps = 0: never
    nc.factorised(reuse)
    assert [_newton_step(reuse, rate, 1e-8, 1e-14, borrowed_steps=0) for _ in range(5)] == [2] * 5
