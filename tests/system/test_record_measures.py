"""The compiled measures of recorded states (energies and tip displacements of every beam, the
strains of ANCF strain gauges,
:func:`hubbeam.system.equations.record_measures`) that the sensors read during a compiled run.

Checked against energies written here from the parts' Python pieces (the ANCF beam's
assembled element mass blocks, elastic energy and gravity load, the tip body's mass matrix
and potential, the FFR part's numpy invariants) and the parts' tip positions and frames
(other code), and the new FFR energy kernel against derivatives
it must have: the elastic force is the gradient of its strain energy, the Newton matrix's mass
block is the Hessian of its kinetic energy in the rates, and the gravity load is minus the
gradient of its potential (finite differences).
"""

from __future__ import annotations

import numpy as np
import pytest

from hubbeam import api
from hubbeam.elements.ffr.constants import pack
from hubbeam.elements.ffr.kernels import ffr_energies, ffr_vspace_terms
from hubbeam.system.rotations import rotation_vector_matrix
from hubbeam.io.scenario import load_example
from hubbeam.simulation import initial_state
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.multibody import energy_sums

CASES = {
    "ancf exp1": ("exp1", []),
    "ffr nodal, stiffened": ("exp1", ['beam.formulation="ffr"', "beam.geometric_stiffening=true"]),
    "ffr modal, stiffened": ("exp1", ['beam.formulation="ffr"', "beam.modes=4", "beam.geometric_stiffening=true"]),
    "three blades, tip bodies": ("rotor3", []),
    "ancf and ffr panels, tip body": ("spacecraft", ['beams[1].formulation="ffr"']),
    "pretwisted tapered blade": ("blade", []),
}


def python_energies(system, x, v, F, beam=None):
    """{kinetic, strain, gravity} (J) of the system (or of beam ``beam``) from the parts' Python pieces."""
    rows = {}
    for k, part, q, chart in system.parts(x, F):
        qd = v[system.layout.beam_x(k)]
        if isinstance(part, FfrPart):  # in v-space: the root frame's motion and p'
            (r, R), (v_r, w) = system._frame_and_rate(k, x, v, F)
            e = part.energies(r, R, q, np.concatenate([v_r, R.T @ w, qd]), system.gravity)
            rows[k] = np.array([e["kinetic"], e["strain"], e["gravity"]])
            continue
        b = part.beam
        row = np.array([0.5 * qd @ b.apply_mass(b.mass_blocks(q, chart), qd), b.elastic(q, chart, tangent=False)[0],
                        -b.gravity_load(system.gravity) @ q])
        if part.tip_body is not None:
            t = part.tip
            _, M, _, _, V = part.tip_body.ancf_terms(chart, q[t], qd[t], np.zeros(8), system.gravity)
            row += [0.5 * qd[t] @ M @ qd[t], 0.0, V]
        rows[k] = row
    if beam is not None:
        return dict(zip(("kinetic", "strain", "gravity"), rows[beam]))
    total = sum(rows.values()) + np.array([0.5 * system.hub.inertia * v[system.theta_index] ** 2, 0.0, 0.0])
    return dict(zip(("kinetic", "strain", "gravity"), total))


def perturbed_states(system, count=3, seed=0):
    rng = np.random.default_rng(seed)
    st = initial_state(system)
    xs = np.array([st.x + 1e-3 * rng.standard_normal(st.x.size) for _ in range(count)])
    vs = np.array([st.v + 0.1 * rng.standard_normal(st.v.size) for _ in range(count)])
    return xs, vs, st.chart


@pytest.mark.parametrize("case", CASES)
def test_compiled_measures_are_the_parts_energies_and_tips(case):
    name, overrides = CASES[case]
    system = api.build_system(load_example(name, overrides))
    xs, vs, chart = perturbed_states(system)
    gauges = [(k, x, y, z) for k, part in enumerate(system.beams) for x in (0.0, 0.37 * part.length, part.length)
              for y, z in ((0.0, 0.001), (0.002, -0.0005))]
    table, kept = system.gauge_table(gauges)
    assert kept == [g for g in gauges if not isinstance(system.beams[g[0]], FfrPart)]
    got = system.record_measures(xs, vs, chart, len(xs), True, table)
    for r in range(len(xs)):
        for beam in [None, *range(len(system.beams))]:
            want = python_energies(system, xs[r], vs[r], chart, beam)
            have = energy_sums(got["hub"][r], got["beams"][r], beam)
            for key, value in want.items():
                assert have[key] == pytest.approx(value, rel=1e-13, abs=1e-15), (beam, key)
        for i, (k, x, y, z) in enumerate(kept):
            assert got["strains"][r, i] == pytest.approx(system.surface_strain(xs[r], chart, x, y, z, k),
                                                         rel=1e-12, abs=1e-15)
        for k in range(len(system.beams)):
            tip = system.tip_displacement(xs[r], k, chart)
            assert np.allclose(got["tips"][r, k], [tip["radial"], tip["vertical"], tip["tangential"]],
                               rtol=0, atol=1e-15)


def test_without_energies_only_tips_are_measured():
    system = api.build_system(load_example("rotor3"))
    xs, vs, chart = perturbed_states(system, 2)
    got = system.record_measures(xs, vs, chart, 2, energies=False)
    assert got["hub"].shape == (0, 3) and got["beams"].shape == (0, 3, 3) and got["tips"].shape == (2, 3, 3)


@pytest.mark.parametrize("modes", [None, 3])
def test_ffr_energies_are_the_potentials_of_its_forces(modes):
    """In v-space (v = [r_C', omega^b, p']): the elastic force is dU/dp, the kinetic energy is
    v^T M_v v / 2 with the kernel's mass matrix, and the gravity load is minus the gradient of
    the gravity potential along r_C, a small turn of the body frame about its own axes and p."""
    overrides = ['beam.formulation="ffr"', "beam.geometric_stiffening=true", "beam.elements=4"]
    system = api.build_system(load_example("exp1", overrides + ([f"beam.modes={modes}"] if modes else [])))
    arrays = pack(system.beams[0])
    inv, tip, drag = arrays.inv, arrays.tip, arrays.drag()
    rng = np.random.default_rng(1)
    nf = system.beams[0].beam.ndof
    n = 6 + nf
    A, r_C = rotation_vector_matrix(rng.normal(size=3)), rng.normal(size=3)
    p = 0.05 * rng.standard_normal(nf)
    vb = rng.standard_normal(n)
    g = np.array([0.3, -9.81, 0.2])
    zero = np.zeros(n)

    def terms(gravity, factor):
        fv, Mv = np.empty(n), np.empty((n, n))
        ffr_vspace_terms(inv, A, p, zero, zero, gravity, tip, drag, factor, False, fv, Mv, np.empty((0, 0)),
                         np.empty((nf, nf)), arrays.work())
        return fv, Mv

    def energies(AA=A, rr=r_C, pp=p, vv=vb):
        return np.array(ffr_energies(inv, AA, rr, pp, vv, g))

    force, Mv = terms(np.zeros(3), 0.0)  # at rest, no loads: the elastic force on p
    h = 1e-6
    for f in range(nf):
        e = np.zeros(nf)
        e[f] = h
        dU = (energies(pp=p + e)[1] - energies(pp=p - e)[1]) / (2 * h)
        assert dU == pytest.approx(force[6 + f], rel=1e-6, abs=1e-9 * np.max(np.abs(force)))
    assert energies()[0] == pytest.approx(0.5 * vb @ Mv @ vb, rel=1e-12)
    load = force - terms(g, 1.0)[0]  # Q_g on v
    grad = np.concatenate([
        [(energies(rr=r_C + h * e)[2] - energies(rr=r_C - h * e)[2]) / (2 * h) for e in np.eye(3)],
        [(energies(AA=A @ rotation_vector_matrix(h * e))[2] - energies(AA=A @ rotation_vector_matrix(-h * e))[2])
         / (2 * h) for e in np.eye(3)],
        [(energies(pp=p + h * e)[2] - energies(pp=p - h * e)[2]) / (2 * h) for e in np.eye(nf)]])
    assert np.allclose(-grad, load, rtol=0, atol=1e-7 * np.max(np.abs(load)))
