"""Campbell diagram: natural frequencies about the steadily rotating state against hub speed,
each mode labelled by its kinetic energy, the modes followed from speed to speed by their
shape (MAC tracking; repeated frequencies as eigenspaces, :func:`hubbeam.solvers.mode_shapes.follow`)
and, on a rotor of N >= 3 identical, evenly spaced beams, read in multi-blade coordinates
(:mod:`hubbeam.solvers.multiblade`): collective, cyclic and differential in the rotating frame,
progressive and regressive whirl in the fixed frame."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from hubbeam import api
from hubbeam.errors import ComputationError
from hubbeam.io.scenario import Scenario
from hubbeam.solvers.modal import rotating_modal_analysis
from hubbeam.solvers.mode_shapes import (CONFIDENT_MAC, SAME_FREQUENCY, blade_vectors, eigenspaces,
                                         energy_fractions, follow, mode_label, motions_of,
                                         plausible_change)
from hubbeam.solvers.multiblade import fixed_frame, harmonic_directions, harmonic_label
from hubbeam.solvers.static import solve_static
from hubbeam.studies.variants import FORMULATIONS, variant

#: the label of a scenario whose beams mix formulations, computed as it is
AS_WRITTEN = "scenario"
#: a branch's frequency may change by this many Hz per rev/s of hub speed between two speeds
#: before its match is penalised and called uncertain (centrifugal stiffening: df/d(Omega/2 pi)
#: is at most the square root of the Southwell coefficient, about 1.1 for a first flap mode)
PLAUSIBLE_SLOPE = 3.0


def spare_modes(count: int) -> int:
    """Modes computed beyond ``count`` at every speed, so that a tracked branch can be found
    when it climbs above a mode that was higher at the previous speed."""
    return max(2, count // 2)


def own_formulation(scenario: Scenario) -> str:
    """The key of :data:`~hubbeam.studies.variants.FORMULATIONS` that every beam of the
    scenario has ("ancf", "ffr", "ffr+"), or :data:`AS_WRITTEN` when they differ."""
    names = {("ffr+" if b.geometric_stiffening else "ffr") if b.formulation == "ffr" else "ancf"
             for b in scenario.resolved_beams()}
    return names.pop() if len(names) == 1 else AS_WRITTEN


def rotor_symmetry(scenario: Scenario) -> tuple[np.ndarray | None, str]:
    """(the beams' azimuths (rad), "") when the scenario's beams form a symmetric rotor: at least
    three beams, identical in everything but their name and azimuth, evenly spaced in their order,
    no tip load, a base at rest, gravity along the hub axis; otherwise (None, the reason, naming
    the first difference)."""
    beams = scenario.resolved_beams()
    if len(beams) < 3:
        return None, f"multi-blade coordinates need at least 3 identical beams (this rotor has {len(beams)})"
    if scenario.base.motion != "fixed":
        return None, (f"multi-blade coordinates need a base at rest (base.motion is {scenario.base.motion!r}: the "
                      "base's motion couples the blades)")
    g = np.asarray(scenario.environment.gravity, dtype=float)
    axis = api.build_system(scenario).hub_axis_rotation[:, 1]
    if np.linalg.norm(np.cross(g, axis)) > 1e-12 * max(np.linalg.norm(g), 1e-300):
        return None, f"environment.gravity {g.tolist()} is not along the hub axis {axis.round(12).tolist()}"
    first = _signature(beams[0])
    for b in beams[1:]:
        other = _signature(b)
        for key, value in first.items():
            if value != other[key]:
                return None, (f"the rotor is not symmetric: {b.name} differs from {beams[0].name} in {key} "
                              f"({_shown(other[key])} against {_shown(value)})")
    for b in beams:
        if any(b.tip_force) or any(b.tip_moment):
            return None, f"the rotor is not symmetric: a tip load acts on {b.name} ([loads])"
    loads = scenario.loads
    if loads.span or loads.tip_force_file is not None or loads.tip_moment_file is not None:
        return None, "the rotor is not symmetric: loads from [loads] act on single beams (span loads or tip tables)"
    from hubbeam.solvers.multiblade import check_azimuths

    psi = np.array([b.azimuth for b in beams])
    try:
        check_azimuths(psi)
    except ValueError:
        return None, (f"the rotor is not symmetric: the azimuths {np.degrees(psi).round(6).tolist()} deg are not "
                      f"evenly spaced in the beams' order (steps of {360 / len(beams):g} deg)")
    return psi, ""


def _signature(beam) -> dict:
    out = {f.name: getattr(beam, f.name) for f in dataclasses.fields(beam)
           if f.name not in ("name", "index", "azimuth", "tip_force", "tip_moment", "sections")}
    s = beam.sections
    out["sections"] = None if s is None else (s.form, s.x.tolist(), s.values.tolist(), s.pretwist.tolist(), s.material)
    return out


def _shown(value) -> str:
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value) if len(str(value)) < 60 else str(value)[:57] + "..."


@dataclass
class _Branches:
    """The tracked branches of one formulation, speed by speed."""

    count: int
    speeds: int
    frequency: np.ndarray = field(init=False)
    label: np.ndarray = field(init=False)
    mac: np.ndarray = field(init=False)
    harmonic: np.ndarray = field(init=False)
    fixed: np.ndarray = field(init=False)
    fixed_label: np.ndarray = field(init=False)
    whirl: np.ndarray = field(init=False)

    def __post_init__(self):
        shape = (self.speeds, self.count)
        self.frequency, self.mac, self.harmonic, self.fixed = (np.full(shape, np.nan) for _ in range(4))
        self.label, self.fixed_label, self.whirl = (np.full(shape, "", dtype=object) for _ in range(3))


def _spaces(system, steady, modes, azimuths):
    """The eigenspaces of one speed as (basis, frequencies, harmonic p or None), ascending; on a
    symmetric rotor each repeated frequency split into its pure harmonics (in the order of
    :func:`~hubbeam.solvers.multiblade.harmonic_orders`), whatever is no single harmonic kept
    as one space with p None."""
    f, V = modes.frequencies_hz, modes.shapes
    groups = eigenspaces(f)
    if azimuths is None:
        return [(V[:, g], f[g], None) for g in groups]
    blades = blade_vectors(system, steady.x, steady.chart, V)
    spaces = []
    for g in groups:
        mean = float(np.mean(f[g]))
        found = harmonic_directions(blades[g], azimuths)
        coefficients = np.zeros((g.size, 0), dtype=complex)
        for p in dict.fromkeys(p for p, _, _ in found):
            c = np.array([c for q, c, _ in found if q == p]).T
            coefficients = np.hstack([coefficients, c])
            basis = V[:, g] @ c
            spaces.append((basis / np.linalg.norm(basis, axis=0), np.full(c.shape[1], mean), p))
        if coefficients.shape[1] < g.size:  # what no single harmonic explains
            rest = np.linalg.svd(coefficients.conj().T, full_matrices=True)[2][coefficients.shape[1]:].conj().T \
                if coefficients.shape[1] else np.eye(g.size)
            basis = V[:, g] @ rest
            spaces.append((basis / np.linalg.norm(basis, axis=0), np.full(rest.shape[1], mean), None))
    return spaces


def campbell(scenario: Scenario, speeds, count: int = 6, formulations=None, harmonics=None,
             progress=None) -> xr.Dataset:
    """Frequencies (Hz) of the lowest ``count`` modes about the steadily rotating state at each
    hub speed (rad/s), for each formulation (default: the scenario's own,
    :func:`own_formulation`). The hub is driven at constant speed; the drag is left out (undamped
    modes about the undamped steady state). Each speed continues from the steady state of the
    previous one. ``progress(done, total)`` as the speeds are done (fractions of a speed too).
    ``harmonics``: the orders n of the nP lines (default 1 .. 2 N for N beams).

    The Dataset holds, over (formulation, omega, mode), the ascending ``frequency_hz``, their
    ``label`` and ``energy_fraction`` (over ``motion``); and over (formulation, omega, branch)
    the *tracked* modes: branch b starts as the b-th mode at the first speed (a repeated
    frequency's modes in the order of their harmonics) and continues at every next speed in the
    eigenspace that :func:`~hubbeam.solvers.mode_shapes.follow` assigns it (among ``count`` +
    :func:`spare_modes` computed, whole eigenspaces kept): ``tracked_frequency_hz``,
    ``tracked_label`` and ``mac`` (the MAC of the branch's shape with its previous one, 1 at the
    first speed); ``branch_label`` (formulation, branch) is the label a branch has at most speeds.
    On a symmetric rotor (:func:`rotor_symmetry`) the labels start with the multi-blade name
    ("collective flap", "cyclic lag", ...), ``harmonic`` holds p, and ``fixed_frequency_hz``,
    ``fixed_label`` ("progressive flap", ...) and ``whirl`` ("forward", "backward", "") give the
    fixed frame. ``np_line_hz`` (order, omega): n Omega / 2 pi. Attributes: ``blades``,
    ``symmetric`` (1 or 0) and ``symmetry`` (why not), ``uncertain`` (one line per uncertain
    match: speed, branch, the match's MAC and frequency change)."""
    speeds = np.asarray(speeds, dtype=float)
    if formulations is None:
        formulations = (own_formulation(scenario),)
    blades = len(scenario.resolved_beams())
    orders = np.arange(1, 2 * blades + 1) if harmonics is None else np.asarray(harmonics, dtype=int)
    azimuths, why = rotor_symmetry(scenario)
    computed = count + spare_modes(count)
    nf, ns = len(formulations), speeds.size
    freq = np.full((nf, ns, count), np.nan)
    labels = np.full((nf, ns, count), "", dtype=object)
    motions = motions_of(api.build_system(scenario))  # joints add their hinges' parts
    fractions = np.full((nf, ns, count, len(motions)), np.nan)
    tracked = [_Branches(count, ns) for _ in formulations]
    uncertain: list[str] = []
    total = nf * ns
    for i, form in enumerate(formulations):
        x0 = chart = previous = None
        for j, omega in enumerate(speeds):
            done = i * ns + j

            def step(fraction):
                if progress:
                    progress(done + fraction, total)

            # no sensors: the diagram reads none, and a free hub's (applied torque) do not hold on a driven one
            sc = variant(scenario, FORMULATIONS.get(form, []) + [
                'hub.motion="prescribed"', 'hub.drive.profile="constant"', f"hub.drive.omega_s={max(omega, 1e-12)}",
                "damping.linear=0.0", "damping.quadratic=0.0", "sensors=[]"])
            system = api.build_system(sc)
            try:
                steady = solve_static(system, load_steps=sc.analysis.load_steps if x0 is None else 2, x0=x0,
                                      chart=chart, spin=omega)
                x0, chart = steady.x, steady.chart
                step(0.3)
                modes = rotating_modal_analysis(system, steady, omega, count=computed, same=SAME_FREQUENCY)
                step(0.7)
                f, shapes = modes.frequencies_hz, modes.shapes
                spaces = _spaces(system, steady, modes, azimuths)
                n = min(count, f.size)
                shares = [energy_fractions(system, steady.x, steady.chart, u) for u in shapes[:, :n].T]
                freq[i, j, :n] = f[:n]
                labels[i, j, :n] = [mode_label(s) for s in shares]
                fractions[i, j, :n] = [[s.get(k, 0.0) for k in motions] for s in shares]
                if previous is None:
                    members = [(b[:, c], fs[c], s) for s, (b, fs, _) in enumerate(spaces) for c in range(b.shape[1])]
                    m = min(count, len(members))
                    current = np.zeros((shapes.shape[0], count), dtype=complex)
                    current[:, :m] = np.array([u for u, _, _ in members[:m]]).T
                    now = np.full(count, np.nan)
                    now[:m] = [fs for _, fs, _ in members[:m]]
                    match, where = np.where(np.arange(count) < m, 1.0, np.nan), np.array(
                        [s for _, _, s in members[:m]] + [-1] * (count - m))
                else:
                    step_hz = PLAUSIBLE_SLOPE * abs(omega - speeds[j - 1]) / (2.0 * np.pi)
                    current, now, match, where = follow(previous, tracked[i].frequency[j - 1], [(b, fs) for b, fs, _ in
                                                                                                 spaces], step_hz)
                    for b in np.flatnonzero(where >= 0):
                        jump = abs(now[b] - tracked[i].frequency[j - 1, b])
                        if match[b] < CONFIDENT_MAC or jump > plausible_change(tracked[i].frequency[j - 1, b], step_hz):
                            uncertain.append(f"{form} branch {b + 1} at omega = {omega:g} rad/s: uncertain match "
                                             f"(MAC {match[b]:.3f} with the previous speed, frequency "
                                             f"{tracked[i].frequency[j - 1, b]:.5g} -> {now[b]:.5g} Hz)")
                _record(tracked[i], j, system, steady, current, now, match, where, spaces, blades, omega)
                previous = np.where(np.isfinite(current), current, previous if previous is not None else 0.0)
            except (ComputationError, np.linalg.LinAlgError, ValueError) as exc:  # say where
                raise ComputationError(f"Campbell diagram, {form} at omega = {omega:g} rad/s: {exc}") from exc
            step(1.0)
    return _dataset(scenario, speeds, formulations, freq, labels, fractions, motions, tracked, orders, azimuths,
                    why, uncertain, blades)


def _record(branches: _Branches, j, system, steady, shapes, freqs, macs, where, spaces, blades, omega) -> None:
    """One speed's tracked branches: frequency, MAC, labels, and their fixed-frame reading."""
    for b in np.flatnonzero(where >= 0):
        p = spaces[where[b]][2]
        motion = mode_label(energy_fractions(system, steady.x, steady.chart, shapes[:, b]))
        branches.frequency[j, b], branches.mac[j, b] = freqs[b], macs[b]
        branches.label[j, b] = motion if p is None else f"{harmonic_label(p, blades, 'rotating')} {motion}"
        if p is not None:
            branches.harmonic[j, b] = p
            fixed, whirl = fixed_frame(freqs[b], p, blades, omega)
            branches.fixed[j, b], branches.whirl[j, b] = float(fixed), str(whirl)
            branches.fixed_label[j, b] = f"{harmonic_label(p, blades, 'fixed')} {motion}"


def _dataset(scenario, speeds, formulations, freq, labels, fractions, motions, tracked, orders, azimuths, why,
             uncertain, blades) -> xr.Dataset:
    count = freq.shape[2]
    stack = {name: np.array([getattr(t, name) for t in tracked]) for name in
             ("frequency", "label", "mac", "harmonic", "fixed", "fixed_label", "whirl")}
    branch_labels = np.array([[_most_common(stack["label"][i, :, b]) for b in range(count)]
                              for i in range(len(formulations))], dtype=object)
    dims = ("formulation", "omega", "branch")
    data = {"frequency_hz": (("formulation", "omega", "mode"), freq, {"units": "Hz"}),
            "label": (("formulation", "omega", "mode"), labels),
            "energy_fraction": (("formulation", "omega", "mode", "motion"), fractions, {"units": "1"}),
            "tracked_frequency_hz": (dims, stack["frequency"], {"units": "Hz"}),
            "tracked_label": (dims, stack["label"]),
            "mac": (dims, stack["mac"], {"units": "1", "long_name": "MAC of the match with the previous speed"}),
            "branch_label": (("formulation", "branch"), branch_labels),
            "np_line_hz": (("order", "omega"), orders[:, None] * speeds[None, :] / (2.0 * math.pi),
                           {"units": "Hz", "long_name": "n Omega / 2 pi: the nP lines"})}
    if azimuths is not None:
        data.update({"harmonic": (dims, stack["harmonic"], {"long_name": "harmonic p of the blade pattern "
                                                             "(0 collective, +-n cyclic, N/2 differential)"}),
                     "fixed_frequency_hz": (dims, stack["fixed"], {"units": "Hz",
                                                                   "long_name": "frequency in the fixed frame"}),
                     "fixed_label": (dims, stack["fixed_label"]),
                     "whirl": (dims, stack["whirl"])})
    ds = xr.Dataset(data, coords={"formulation": list(formulations), "omega": ("omega", speeds, {"units": "rad/s"}),
                                  "mode": np.arange(1, count + 1), "branch": np.arange(1, count + 1),
                                  "motion": list(motions), "order": orders})
    ds.attrs.update({"scenario": scenario.name, "blades": blades, "symmetric": int(azimuths is not None),
                     "symmetry": why, "uncertain": "\n".join(uncertain)})
    return ds


def _most_common(values) -> str:
    names, counts = np.unique([str(v) for v in values if v], return_counts=True)
    return str(names[np.argmax(counts)]) if names.size else ""
