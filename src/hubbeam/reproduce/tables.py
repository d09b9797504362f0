"""The paper's tables from the runs, beside its published values (tables.json rows)."""

from __future__ import annotations

import json

import numpy as np

from hubbeam.analysis.frequency import dominant_frequency
from hubbeam.reproduce import paper
from hubbeam.reproduce.plan import MODAL_MODES, Plan, mesh_of


def _frequency(ds, name: str) -> float | None:
    if ds is None or name not in ds:
        return None
    return dominant_frequency(ds["time"].values, ds[name].values).frequency_hz


def _pct(value, reference):
    """Relative difference in percent; for deflections (signed, same sign) use :func:`_pct_size`."""
    if value is None or reference is None:
        return None
    return 100.0 * (value - reference) / abs(reference)


def _pct_size(value, reference):
    """How much larger (+) or smaller (-) |value| is than |reference|, in percent."""
    if value is None or reference is None:
        return None
    return 100.0 * (abs(value) / abs(reference) - 1.0)


def _final(ds, name: str, t_end: float):
    """The last value of a variable, or None if the run stopped before t_end."""
    if ds is None or abs(float(ds["time"].values[-1]) - t_end) > 1e-6:
        return None
    return float(ds[name].values[-1])


def _beam(ds):
    """The (single) beam of the run's scenario, resolved (SI units, radians)."""
    from hubbeam.io.scenario import validate
    from hubbeam.studies.variants import single_beam

    return single_beam(validate(json.loads(ds.attrs["scenario"])), "the reproduction")


def _deflection_along_kb(ds) -> np.ndarray:
    """Tip displacement along the clamp's k_b = sin(beta) j_h + cos(beta) k_h (the weak axis)."""
    beta = _beam(ds).twist
    return np.sin(beta) * ds["tip_vertical"].values + np.cos(beta) * ds["tip_tangential"].values


#: the tables.json key of each formulation's rows (Tables 2 and 5)
ROWS = {"ancf": "ancf", "ffr": "ffr", "ffr+": "ffr_stiffened", "ffr-modal": "ffr_modal"}


def _dof(form: str, n: int) -> int:
    """The paper's DOF count (:func:`paper.dof`); for modal FFR its elastic coordinates: the kept
    modes, plus with geometric stiffening one axial coordinate per element (docs/ffr.md)."""
    if form == "ffr-modal":
        return MODAL_MODES + n
    return paper.dof(mesh_of(form), n)


def _row(form: str, n: int) -> dict:
    row = {"dof": _dof(form, n), "elements": n}
    if form == "ffr-modal":
        row["modes"] = MODAL_MODES
    return row


def table2(plan: Plan, outcomes) -> dict:
    out = {"experiment_hz": paper.TABLE2["experiment_hz"], "ancf": [], "ffr": [], "ffr_modal": []}
    for (form, n), case in plan.table2_cases().items():
        ds = outcomes[case.key].dataset
        f = _frequency(ds, "strain_P1")
        row = _row(form, n)
        row.update({
            "frequency_hz": f,
            "hub_omega_frequency_hz": _frequency(ds, "hub_omega"),
            "resolution_hz": 1.0 / plan.exp1_time,
            "error_vs_experiment_pct": _pct(f, paper.TABLE2["experiment_hz"]),
        })
        if form in paper.TABLE2:
            row["paper_hz"] = paper.TABLE2[form].get(row["dof"])
        out[ROWS[form]].append(row)
    return out


def table3(plan: Plan, outcomes) -> dict:
    rows = []
    for example in ("exp1_h4", "exp1", "exp1_h1"):
        ds = {form: outcomes[plan.table3_cases()[example, form].key].dataset
              for form in ("ancf", "ffr", "ffr+", "ffr-modal")}
        if ds["ancf"] is None:
            continue
        beam = _beam(ds["ancf"])
        length = beam.length
        fa, ff = _frequency(ds["ancf"], "strain_P1"), _frequency(ds["ffr"], "strain_P1")
        fs, fm = _frequency(ds["ffr+"], "strain_P1"), _frequency(ds["ffr-modal"], "strain_P1")
        wm = float(np.max(np.abs(_deflection_along_kb(ds["ancf"]))))
        rows.append({
            "thickness_m": beam.thickness,
            "ancf_frequency_hz": fa, "ffr_frequency_hz": ff, "ffr_vs_ancf_pct": _pct(ff, fa),
            "ffr_stiffened_frequency_hz": fs, "ffr_stiffened_vs_ancf_pct": _pct(fs, fa),
            "ffr_modal_frequency_hz": fm, "ffr_modal_vs_ancf_pct": _pct(fm, fa),
            "w_m": wm, "w_m_over_L": wm / length,
            "ffr_w_m": float(np.max(np.abs(_deflection_along_kb(ds["ffr"])))) if ds["ffr"] is not None else None,
        })
    return {"rows": rows, "paper_limit_w_m_over_L": paper.FFR_DEFLECTION_LIMIT}


def table5(plan: Plan, outcomes) -> dict:
    out = {"experiment_m": paper.TABLE5["experiment_m"], "time_s": plan.exp2_time, "ancf": [], "ffr": [],
           "ffr_stiffened": [], "ffr_modal": []}
    for (form, n), case in plan.table5_cases().items():
        ds = outcomes[case.key].dataset
        tip = _final(ds, "tip_tangential", plan.exp2_time)
        row = _row(form, n)
        row.update({"tip_deflection_m": tip, "error_vs_experiment_pct": _pct_size(tip, paper.TABLE5["experiment_m"])})
        if form in paper.TABLE5:
            row["paper_m"] = paper.TABLE5[form].get(row["dof"])
        out[ROWS[form]].append(row)
    return out


def table6(plan: Plan, outcomes) -> dict:
    omega1 = 2 * np.pi * paper.MEASURED_FIRST_HZ
    rows = []
    for omega in plan.speeds:
        vals = {}
        for form in ("ancf", "ffr", "ffr+", "ffr-modal"):
            ds = outcomes[plan.table6_cases()[omega, form].key].dataset
            vals[form] = _final(ds, "tip_tangential", plan.exp2_time)
            if form == "ancf":
                omega_m = _final(ds, "hub_omega", plan.exp2_time)
        rows.append({"omega_s": omega, "omega_m": omega_m, "omega_m_over_omega_1": omega_m / omega1 if omega_m else None,
                     "ancf_tip_deflection_m": vals["ancf"], "ffr_tip_deflection_m": vals["ffr"],
                     "ffr_stiffened_tip_deflection_m": vals["ffr+"], "ffr_vs_ancf_pct": _pct_size(vals["ffr"], vals["ancf"]),
                     "ffr_stiffened_vs_ancf_pct": _pct_size(vals["ffr+"], vals["ancf"]),
                     "ffr_modal_tip_deflection_m": vals["ffr-modal"],
                     "ffr_modal_vs_ancf_pct": _pct_size(vals["ffr-modal"], vals["ancf"])})
    return {"rows": rows, "omega_1_rad_s": omega1, "paper_limit_omega_m_over_omega_1": paper.FFR_SPEED_LIMIT,
            "elements": dict(plan.fine), "ffr_modal_modes": MODAL_MODES}


def all_tables(plan: Plan, outcomes) -> dict:
    return {"table2": table2(plan, outcomes), "table3": table3(plan, outcomes), "table5": table5(plan, outcomes),
            "table6": table6(plan, outcomes)}
