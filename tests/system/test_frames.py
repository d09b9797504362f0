"""Frame chains (system/frames.py): every Jacobian and derivative against central differences of
the pose, which is computed by products of plain rotation matrices (no derivative formulas)."""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.elements.ancf.frame import frame_global
from hubbeam.system import frames as fr
from hubbeam.system import rotations as rot
from hubbeam.system import chains as ch


def _skew_axial(A):
    """axial vector of the skew part of A."""
    return 0.5 * np.array([A[2, 1] - A[1, 2], A[0, 2] - A[2, 0], A[1, 0] - A[0, 1]])


def _random_rotation(rng):
    return rot.rotation_vector_matrix(rng.normal(size=3))


def _chains(rng):
    """(name, chain, x, F): chains with every link kind, at random coordinates."""
    x = rng.normal(size=40)
    x[3:7] *= 1.7  # Euler parameters of any norm (the pose normalises them)
    F = np.array([frame_from_director(rng.normal(size=3)), frame_from_director(rng.normal(size=3))])
    # an ANCF node: position, slope away from the chart's singular direction, twist
    x[20:23] = rng.normal(size=3)
    x[23:26] = F[1][:, 0] * 1.1 + 0.3 * rng.normal(size=3)
    const = lambda: ch.constant(rng.normal(size=3), _random_rotation(rng))  # noqa: E731
    hub = ch.Chain((const(), ch.revolute(10, (0.0, 1.0, 0.0), -1.0), const()))
    base = ch.Chain((ch.free(0), const(), ch.revolute(10, (0.0, 1.0, 0.0), -1.0), const(),
                     ch.revolute(11, rng.normal(size=3)), ch.revolute(12, rng.normal(size=3)), const()))
    tip = ch.Chain((ch.ancf_tip(20, 1), const(), ch.revolute(13, (1.0, 0.0, 0.0)), const()))
    # FFR tips: an elastic beam's tip moved by its coordinates (5 at x[30:35], 4 at x[35:39])
    x[30:39] *= 0.3
    ffr = lambda c, nf: ch.ffr_tip(c, 1.7, rng.normal(size=(3, nf)), rng.normal(size=(3, nf)))  # noqa: E731
    on_hub = ch.Chain((const(), ch.revolute(10, (0.0, 1.0, 0.0), -1.0), const(), ch.revolute(11, (0.0, 0.0, 1.0)),
                       ffr(30, 5), const(), ch.revolute(12, (0.0, 1.0, 0.0)), ffr(35, 4), const()))
    on_ancf = ch.Chain((ch.ancf_tip(20, 1), ffr(30, 5), ch.revolute(13, rng.normal(size=3)), const()))
    on_base = ch.Chain((ch.free(0), ch.revolute(10, (0.0, 1.0, 0.0), -1.0), ffr(30, 5), ffr(35, 4)))
    return [("hub", hub, x, F), ("base", base, x, F), ("ancf tip", tip, x, F), ("ffr tips on a hub", on_hub, x, F),
            ("ffr tip on an ancf tip", on_ancf, x, F), ("ffr tips on a free base", on_base, x, F)]


def _pose(chain, x, F):
    r, R, *_ = fr.chain_pose(ch.ChainTable.of([chain]), 0, x, F)
    return r, R


def _reference_pose(chain, x, F):
    """The pose by plain matrix products (no code shared with chain_kinematics's derivatives)."""
    r, R = np.zeros(3), np.eye(3)
    for link in chain.links:
        if link.kind == ch.LinkKind.CONSTANT:
            r = r + R @ np.array(link.offset)
            R = R @ np.array(link.rotation)
        elif link.kind == ch.LinkKind.REVOLUTE:
            axis = np.array(link.axis) / np.linalg.norm(link.axis)
            R = R @ rot.rotation_vector_matrix(link.sign * x[link.coordinate] * axis)
        elif link.kind == ch.LinkKind.FREE:
            e = x[link.coordinate + 3 : link.coordinate + 7]
            e = e / np.linalg.norm(e)
            e0, v = e[0], e[1:]
            V = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
            r = x[link.coordinate : link.coordinate + 3].copy()
            R = (e0 * e0 - v @ v) * np.eye(3) + 2 * np.outer(v, v) + 2 * e0 * V
        elif link.kind == ch.LinkKind.FFR_TIP:
            M = np.array(link.rows)
            v = M @ x[link.coordinate : link.coordinate + M.shape[1]]
            r = r + R @ (np.array([link.length, 0.0, 0.0]) + v[0:3])
            for a in range(3):  # x, then y', then z''
                R = R @ rot.rotation_vector_matrix(v[3 + a] * np.eye(3)[a])
        else:
            c = link.coordinate
            r = x[c : c + 3].copy()
            R = frame_global(F[link.chart], x[c + 3 : c + 6], x[c + 6])
    return r, R


@pytest.mark.parametrize("which", range(6))
def test_pose_jacobians_and_derivatives_against_differences(which):
    rng = np.random.default_rng(7 + which)
    name, chain, x, F = _chains(rng)[which]
    table = ch.ChainTable.of([chain])
    r, R, Jr, Jw, Hr, Hw = fr.chain_pose(table, 0, x, F, order=2)
    r_ref, R_ref = _reference_pose(chain, x, F)
    assert np.allclose(r, r_ref, atol=1e-13) and np.allclose(R, R_ref, atol=1e-13), name
    assert np.allclose(R.T @ R, np.eye(3), atol=1e-13)
    cols = chain.coordinates
    h = 1e-6
    for i, c in enumerate(cols):
        xp, xm = x.copy(), x.copy()
        xp[c] += h
        xm[c] -= h
        rp, Rp = _reference_pose(chain, xp, F)
        rm, Rm = _reference_pose(chain, xm, F)
        dR = (Rp - Rm) / (2 * h)
        assert np.allclose((rp - rm) / (2 * h), Jr[:, i], atol=1e-8), (name, i)
        w = _skew_axial(dR @ R.T)  # dR/dc = [w]x R
        assert np.allclose(w, Jw[:, i], atol=1e-8), (name, i)
        # derivatives of the Jacobians along this column
        *_, Jrp, Jwp, _, _ = fr.chain_pose(table, 0, xp, F)
        *_, Jrm, Jwm, _, _ = fr.chain_pose(table, 0, xm, F)
        assert np.allclose((Jrp - Jrm) / (2 * h), Hr[:, :, i], atol=1e-7), (name, i)
        assert np.allclose((Jwp - Jwm) / (2 * h), Hw[:, :, i], atol=1e-7), (name, i)


def test_euler_parameters_and_rotation_vectors_round_trip():
    rng = np.random.default_rng(3)
    for _ in range(20):
        phi = rng.normal(size=3)
        phi *= rng.uniform(0, np.pi) / np.linalg.norm(phi)
        R = rot.rotation_vector_matrix(phi)
        assert np.allclose(rot.rotation_vector(R), phi, atol=1e-12)
        e = rot.euler_parameters(R)
        R2 = np.empty((3, 3))
        rot.euler_rotation(e, R2)
        assert np.allclose(R2, R, atol=1e-13)


def test_an_ffr_tip_turns_by_its_rotation_vector_to_first_order():
    """The tip link's x-y'-z'' rotation of phi = Phi p and the rotation vector phi (FFR's
    kinematics, Eq. 43) differ at second order in phi only; an FFR tip cannot start a chain."""
    rows = np.vstack([np.zeros((3, 3)), np.eye(3)])
    chain = ch.Chain((ch.constant(), ch.ffr_tip(0, 2.0, rows[:3], rows[3:])))
    phi = np.array([0.3, -0.2, 0.5])
    for eps in (1e-2, 1e-3):
        r, R = _pose(chain, eps * phi, None)
        assert np.allclose(r, [2.0, 0.0, 0.0])
        gap = np.max(np.abs(R - rot.rotation_vector_matrix(eps * phi)))
        assert gap < 0.2 * eps**2
    with pytest.raises(ValueError, match="cannot be the first"):
        ch.Chain((ch.ffr_tip(0, 2.0, rows[:3], rows[3:]),))


def test_a_table_flags_the_link_kinds_it_holds():
    """ChainTable.of sets free_links, ancf_tips and ffr_tips to True exactly for the kinds some chain
    holds (None otherwise): the compiled kinematics leave out the code of a kind flagged None."""
    chains = _chains(np.random.default_rng(3))
    for name, chain, _, _ in chains + [("all", None, None, None)]:
        held = {link.kind for c in ([chain] if chain else [c for _, c, _, _ in chains]) for link in c.links}
        table = ch.ChainTable.of([chain] if chain else [c for _, c, _, _ in chains])
        expected = tuple(True if kind in held else None
                         for kind in (ch.LinkKind.FREE, ch.LinkKind.ANCF_TIP, ch.LinkKind.FFR_TIP))
        assert (table.free_links, table.ancf_tips, table.ffr_tips) == expected, name
    assert ch.ChainTable.of([chains[0][1]])[-3:] == (None, None, None)  # the hub: constants and revolutes


@pytest.mark.parametrize("which", [0, 1])
def test_the_pruned_kinematics_equal_the_whole_code(which):
    """A table evaluated by the kinematics compiled for the kinds it holds (the hub's chain:
    constants and revolutes; the base's: a free link too) gives the same pose, Jacobians and
    derivatives as the code compiled with every kind of link."""
    name, chain, x, F = _chains(np.random.default_rng(11 + which))[which]
    table = ch.ChainTable.of([chain])
    assert None in table[-3:], name
    out = []
    for flags in (table[-3:], (True, True, True)):
        pose, jac, hess = np.zeros_like(table.pose), np.zeros_like(table.jac), np.zeros_like(table.hess)
        fr.chain_kinematics_into(table, 0, table.orders.shape[0], x, F, 2, table.orders, pose, jac, hess,
                                 np.zeros_like(table.work), *flags, x, np.zeros_like(table.products), False)
        out.append((pose, jac, hess))
    for a, b in zip(*out):
        assert np.array_equal(a, b), name


def test_exp1_compiles_its_chains_without_the_other_kinds():
    """exp1 (a fixed base, a hub, one ANCF beam on it: constants and revolutes) has its chains'
    kinematics compiled once, for an int64 order with every other kind's flag None, for the
    Python front end, the equations and the tips alike (on a cold cache all three compile it;
    on a warm one the first loads it): no second signature for a literal order (one copy per
    literal 1 and 2) nor for arrays of another layout."""
    from numba import typeof, types

    from hubbeam import api
    from hubbeam.io.scenario import load_example
    from hubbeam.system.assembly import BorderedBandMatrix
    from hubbeam.system.equations import system_equations, tip_displacements

    from hubbeam.simulation import initial_state

    system = api.build_system(load_example("exp1"))
    model, layout = system.model(), system.layout
    table_type = typeof(model.context.chains)
    before = [s for s in fr.chain_kinematics_into.signatures if s[0] == table_type]  # other tests' tables
    state = initial_state(system)
    x, F = state.x, np.ascontiguousarray(state.chart)
    res = np.empty(layout.nz)
    mat = BorderedBandMatrix.empty(layout.nz, layout.border, model.bandwidth)
    system_equations(model, F, x, state.v, state.xdd, state.lam, 0.0, 1.0, 0.5, 0.25, 1.0, 1.0, False, True, res,
                     mat.ab, mat.brow, mat.bcol, mat.bb)
    tip_displacements(model, F, x, np.empty((1, 3)))
    fr.chain_pose(model.context.chains, 0, x, F, 2)
    signatures = [s for s in fr.chain_kinematics_into.signatures if s[0] == table_type]
    assert any(all(t == types.none for t in s[11:14]) for s in signatures)
    assert not any(isinstance(t, types.Literal) for s in signatures for t in s)  # a copy per literal
    assert all(t.layout == "C" for s in signatures for t in s if isinstance(t, types.Array))
    assert len(signatures) - len(before) <= 1


@pytest.mark.parametrize("which", range(6))
def test_velocity_products_against_differences_of_the_jacobians(which):
    """evaluate_motion's velocity products h = sum_il H[:, i, l] c'_i c'_l of a chain marked for
    them alone (a free body and screws: summed in one pass without H; an ANCF or FFR tip:
    contracted from H) and of one marked for its Hessians equal d(J c')/dt at fixed c' = (J(x +
    e v) - J(x - e v)) / (2 e) c', from the Jacobians of the pose alone (no second derivative).
    A wrong sign or a missed pair of columns in the one-pass sum (the free body's own columns,
    the pairs l > i) would show."""
    rng = np.random.default_rng(31 + which)
    name, chain, x, F = _chains(rng)[which]
    v = rng.normal(size=x.size)
    cols = chain.coordinates
    eps = 1e-6
    *_, Jrp, Jwp, _, _ = fr.chain_pose(ch.ChainTable.of([chain]), 0, x + eps * v, F)
    *_, Jrm, Jwm, _, _ = fr.chain_pose(ch.ChainTable.of([chain]), 0, x - eps * v, F)
    expected = np.array([(Jrp - Jrm) @ v[cols], (Jwp - Jwm) @ v[cols]]) / (2 * eps)
    for hessians in (None, set()):  # marked for its Hessians, for its products alone
        table = ch.ChainTable.of([chain], {0}, hessians)
        assert table.orders[0] == (ch.HESSIANS if hessians is None else ch.PRODUCTS)
        table.hess[...] = np.nan if hessians is not None and which in (0, 1) else 0.0  # the one pass reads no H
        fr.evaluate_motion(table, x, v, np.ascontiguousarray(F), False)
        assert np.allclose(table.products[0], expected, rtol=1e-7, atol=1e-7 * np.max(np.abs(expected))), name


def test_chains_that_begin_with_another_continue_from_its_pose():
    """In one table, a chain whose links begin with an earlier chain's (a free base's frames: the
    base, the hub on it, the roots on the hub) continues from that chain's pose and Jacobians
    (ChainTable.prefix): its pose, Jacobians and velocity products equal those of the chain
    evaluated alone, from its first link (round-off apart); one that holds a tip shares
    nothing."""
    rng = np.random.default_rng(5)
    x, v = rng.normal(size=20), rng.normal(size=20)
    const = lambda: ch.constant(rng.normal(size=3), _random_rotation(rng))  # noqa: E731
    base = ch.Chain((ch.free(0), const()))
    hub = base.then(ch.revolute(7, (0.0, 1.0, 0.0), -1.0))
    chains = [base, hub, hub.then(const()), hub.then(const(), ch.revolute(8, rng.normal(size=3)), const()), hub,
              hub.then(ch.ffr_tip(9, 1.5, rng.normal(size=(3, 4)), rng.normal(size=(3, 4))))]
    table = ch.ChainTable.of(chains, set(range(len(chains))), set())
    assert list(table.prefix) == [-1, 0, 1, 1, 1, -1]
    F = np.zeros((1, 3, 3))
    fr.evaluate_motion(table, x, v, F, False)
    for k, chain in enumerate(chains):
        alone = ch.ChainTable.of([chain], {0}, set())
        fr.evaluate_motion(alone, x, v, F, False)
        nc = table.width(k)
        for mine, its in ((table.pose[k], alone.pose[0]), (table.jac[k][:, :, :nc], alone.jac[0][:, :, :nc]),
                          (table.products[k], alone.products[0])):
            np.testing.assert_allclose(mine, its, rtol=0, atol=1e-13 * max(1.0, np.max(np.abs(its))))
