"""Figures, report.md and tables.json of a reproduction."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from hubbeam import plots
from hubbeam.reproduce import paper
from hubbeam.reproduce.plan import MODAL_MODES, Plan

PROPERTIES_NOTE = (
    "**The beam properties are inferred, not read from the paper.** Its Tables 1 and 4 (material "
    "and geometry of the beams of experiments 1 and 2) are images missing from its text. hubbeam uses "
    "the reference set of the README (\"Beam properties\"): L = 1.45 m (0.55 m is 38 % of it), b = 0.05 m (assumed), "
    "h = 2.5 mm (gives a 0.978 Hz clamped first frequency against 0.9766 Hz measured), aluminium "
    "E = 70 GPa, nu = 0.33, rho = 2700 kg/m^3, for both experiments. Nothing (properties, damping, "
    "meshes) is adjusted to meet the paper's numbers.")


def _f(value, spec=".4f", suffix=""):
    return "—" if value is None else f"{value:{spec}}{suffix}"


def _datasets(plan: Plan, outcomes, cases: dict, labels: dict) -> dict:
    out = {}
    for key, label in labels.items():
        ds = outcomes[cases[key].key].dataset
        if ds is not None:
            out[label] = ds
    return out


def figures(plan: Plan, outcomes, tables, directory: Path) -> dict[str, str]:
    """Write the PNG figures; returns {figure id: file name}."""
    files = {}
    fine = plan.fine
    t3 = plan.table3_cases()
    for example, fid, title in (("exp1", "fig5_6", "h = 2.5 mm"), ("exp1_h4", "fig7_8", "h = 4 mm"),
                                ("exp1_h1", "fig9_10", "h = 1 mm")):
        labels = {(example, "ancf"): f"ANCF, {fine['ancf']} elements", (example, "ffr"): f"FFR, {fine['ffr']} elements"}
        data = _datasets(plan, outcomes, t3, labels)
        if data:
            variables = ["strain_P1", "strain_P2", "hub_omega"] if example == "exp1" else ["strain_P1", "hub_omega"]
            files[fid] = f"{fid}_{example}.png"
            plots.plot_comparison(data, directory / files[fid], variables,
                                  title=f"Experiment 1, {title}: upper-surface strain and hub angular velocity")
    t6 = plan.table6_cases()
    labels = {(3.05, "ancf"): f"ANCF, {fine['ancf']} elements", (3.05, "ffr"): f"FFR, {fine['ffr']} elements",
              (3.05, "ffr+"): f"FFR + geometric stiffening, {fine['ffr']} elements",
              (3.05, "ffr-modal"): f"{LABELS['ffr_modal']}, from {fine['ffr']} elements"}
    data = _datasets(plan, outcomes, t6, labels)
    if data:
        files["fig12"] = "fig12_drive.png"
        plots.plot_comparison({k: v for k, v in list(data.items())[:1]}, directory / files["fig12"], ["hub_omega"],
                              title="Experiment 2: the drive's angular velocity (Eq. 81)")
        files["fig13"] = "fig13_tip.png"
        plots.plot_comparison(data, directory / files["fig13"], ["tip_tangential"],
                              title="Experiment 2: tip deflection (tangential, negative = lagging)")
    rows = [r for r in tables["table6"]["rows"] if r["omega_m"] is not None]
    if rows:
        x = np.array([r["omega_m_over_omega_1"] for r in rows])
        series = {name: (x, np.array([np.nan if r[key] is None else r[key] for r in rows]))
                  for name, key in (("ANCF", "ancf_tip_deflection_m"), ("FFR", "ffr_tip_deflection_m"),
                                    ("FFR + stiffening", "ffr_stiffened_tip_deflection_m"),
                                    (LABELS["ffr_modal"], "ffr_modal_tip_deflection_m"))}
        files["table6"] = "table6_speeds.png"
        plots.plot_xy(series, directory / files["table6"], "omega_m / omega_1 (omega_1 = 2 pi 0.9766 Hz)",
                      "tip deflection at 80 s (m)", "Experiment 2 at other drive speeds (Table 6)",
                      vline=paper.FFR_SPEED_LIMIT)
        errors = {name: (x, np.array([np.nan if r[key] is None else r[key] for r in rows]))
                  for name, key in (("FFR", "ffr_vs_ancf_pct"), ("FFR + stiffening", "ffr_stiffened_vs_ancf_pct"),
                                    (LABELS["ffr_modal"], "ffr_modal_vs_ancf_pct"))}
        files["table6_error"] = "table6_ffr_error.png"
        plots.plot_xy(errors, directory / files["table6_error"], "omega_m / omega_1", "|FFR| / |ANCF| - 1 (%)",
                      "FFR's tip-deflection error against ANCF (dashed: the paper's 33 %)", vline=paper.FFR_SPEED_LIMIT)
    return files


#: the row labels of the tables.json row lists
LABELS = {"ancf": "ANCF", "ffr": "FFR", "ffr_stiffened": "FFR + stiffening",
          "ffr_modal": f"FFR, {MODAL_MODES} modes + stiffening"}


def _table2_md(t2) -> list[str]:
    lines = ["| formulation | DOF | elements | ours, P1 (Hz) | ours, hub ω (Hz) | error vs 1.0052 Hz | paper (Hz) |",
             "|---|---|---|---|---|---|---|"]
    for form in ("ancf", "ffr", "ffr_modal"):
        for r in t2.get(form, []):
            lines.append(f"| {LABELS[form]} | {r['dof']} | {r['elements']} | {_f(r['frequency_hz'])} | "
                         f"{_f(r['hub_omega_frequency_hz'])} | {_f(r['error_vs_experiment_pct'], '+.2f', ' %')} | "
                         f"{_f(r.get('paper_hz'))} |")
    return lines


def _table3_md(t3) -> list[str]:
    lines = ["| h (mm) | ANCF (Hz) | FFR (Hz) | FFR vs ANCF | FFR + stiffening (Hz) | vs ANCF | " + LABELS["ffr_modal"]
             + " (Hz) | vs ANCF | w_m (m, ANCF) | w_m / L |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in t3["rows"]:
        lines.append(f"| {1000 * r['thickness_m']:.1f} | {_f(r['ancf_frequency_hz'])} | {_f(r['ffr_frequency_hz'])} | "
                     f"{_f(r['ffr_vs_ancf_pct'], '+.1f', ' %')} | {_f(r.get('ffr_stiffened_frequency_hz'))} | "
                     f"{_f(r.get('ffr_stiffened_vs_ancf_pct'), '+.1f', ' %')} | {_f(r.get('ffr_modal_frequency_hz'))} | "
                     f"{_f(r.get('ffr_modal_vs_ancf_pct'), '+.1f', ' %')} | {_f(r['w_m'], '.3f')} | "
                     f"{_f(r['w_m_over_L'], '.2f')} |")
    return lines


def _table5_md(t5) -> list[str]:
    lines = ["| formulation | DOF | elements | ours (m) | size vs −0.076 m measured | paper (m) |", "|---|---|---|---|---|---|"]
    for form in ("ancf", "ffr", "ffr_stiffened", "ffr_modal"):
        for r in t5.get(form, []):
            lines.append(f"| {LABELS[form]} | {r['dof']} | {r['elements']} | {_f(r['tip_deflection_m'])} | "
                         f"{_f(r['error_vs_experiment_pct'], '+.1f', ' %')} | {_f(r.get('paper_m'))} |")
    return lines


def _table6_md(t6) -> list[str]:
    lines = ["| ω_s (rad/s) | ω_m (rad/s) | ω_m / ω_1 | ANCF (m) | FFR (m) | FFR size vs ANCF | FFR + stiffening (m) | "
             f"size vs ANCF | {LABELS['ffr_modal']} (m) | size vs ANCF |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in t6["rows"]:
        lines.append(f"| {r['omega_s']:g} | {_f(r['omega_m'], '.3f')} | {_f(r['omega_m_over_omega_1'], '.2f')} | "
                     f"{_f(r['ancf_tip_deflection_m'])} | {_f(r['ffr_tip_deflection_m'])} | "
                     f"{_f(r['ffr_vs_ancf_pct'], '+.1f', ' %')} | {_f(r['ffr_stiffened_tip_deflection_m'])} | "
                     f"{_f(r['ffr_stiffened_vs_ancf_pct'], '+.1f', ' %')} | {_f(r.get('ffr_modal_tip_deflection_m'))} | "
                     f"{_f(r.get('ffr_modal_vs_ancf_pct'), '+.1f', ' %')} |")
    return lines


def _exp1_discussion(t2, t3, record_s: float) -> str:
    a = [r for r in t2["ancf"] if r["frequency_hz"] is not None]
    f = [r for r in t2["ffr"] if r["frequency_hz"] is not None]
    if not a or not f:
        return "Some runs of experiment 1 failed; see the failures above."
    fa, ff = a[-1]["frequency_hz"], f[-1]["frequency_hz"]
    spread = max(r["frequency_hz"] for r in a) - min(r["frequency_hz"] for r in a)
    text = (f"With the finest meshes, ANCF gives {fa:.4f} Hz ({a[-1]['error_vs_experiment_pct']:+.2f} % against the "
            f"measured 1.0052 Hz) and FFR {ff:.4f} Hz ({f[-1]['error_vs_experiment_pct']:+.2f} %). "
            f"{'As in the paper, FFR' if ff < fa else 'Unlike the paper, FFR'} is the lower of the two: its linear "
            "strain and small-deformation kinematics miss the shortening and the geometric coupling of a beam that "
            "sags by a large fraction of its length. ")
    if len(a) > 1:
        text += (f"Our ANCF frequencies change by {spread:.4f} Hz between {a[0]['elements']} and {a[-1]['elements']} "
                 "elements, while the paper's fall from 1.0938 to 1.0145 Hz" +
                 (": our element (exact strain Hessians, 5 Gauss points) is already converged on the coarse meshes, "
                  "so the paper's mesh trend is not reproduced. " if spread < 0.02 else ". "))
    text += (f"The spectral resolution of a {record_s:g} s record is {1 / record_s:.3g} Hz; the interpolated peak "
             "locates one isolated component far more finely, but differences well below that should not be read as "
             "physics. ")
    text += ("The absolute level depends on the inferred thickness (the first frequency scales with h), so agreement "
             "with 1.0052 Hz to a few percent is what the inferred properties allow, not a validation. ")
    rows = [r for r in t3["rows"] if r["ffr_vs_ancf_pct"] is not None]
    if rows:
        parts = [f"h = {1000 * r['thickness_m']:.1f} mm: w_m/L = {r['w_m_over_L']:.2f}, FFR {r['ffr_vs_ancf_pct']:+.1f} %"
                 for r in rows]
        text += ("Table 3: the FFR–ANCF frequency gap grows with the deflection (" + "; ".join(parts) + "). The paper "
                 f"places the threshold at w_m/L = {paper.FFR_DEFLECTION_LIMIT:.2f}.")
    both = [r for r in rows if r.get("ffr_modal_frequency_hz") is not None and r.get("ffr_stiffened_frequency_hz")]
    if both:
        gap = max(abs(r["ffr_modal_frequency_hz"] / r["ffr_stiffened_frequency_hz"] - 1) for r in both)
        text += (f" FFR on {MODAL_MODES} modes (with the geometric stiffening and its axial coordinates) stays within "
                 f"{100 * gap:.2g} % of the nodal FFR with stiffening" +
                 (", so where it departs from the plain FFR column it is the stiffening of the sagging beam that "
                  "moves it, not the modal truncation." if gap < 0.005 else "."))
    return text


def _exp2_discussion(t5, t6) -> str:
    a = [r for r in t5["ancf"] if r["tip_deflection_m"] is not None]
    f = [r for r in t5["ffr"] if r["tip_deflection_m"] is not None]
    if not a or not f:
        return "Some runs of experiment 2 failed; see the failures above."
    ta, tf = a[-1]["tip_deflection_m"], f[-1]["tip_deflection_m"]
    measured = paper.TABLE5["experiment_m"]
    ratio = ta / measured
    text = (f"Our ANCF tip deflection at {t5_time(t5):g} s is {ta:.4f} m against {measured} m measured ({ratio:.2f} times) "
            f"and {paper.TABLE5['ancf'][56]} m from the paper's ANCF. ")
    if not 0.8 < ratio < 1.25:
        text += ("**This is a real disagreement.** At 3 rad/s the tip moves at about 6 m/s and the drag of Eq. 37 "
                 "(b (c1 v + c2 v^2) per unit length) is of the order of the beam's weight; with beta = 0 it loads the "
                 "weak axis, so the lag is mostly drag-driven and scales like b / (E b h^3), that is like 1/h^3 and "
                 "independently of the assumed width. The beam of experiment 2 is described by the missing Table 4, "
                 "which need not be the beam of Table 1; a plate about "
                 f"{2.5 * ratio ** (1 / 3):.1f} mm thick would lag about as measured (a 1/h^3 scaling estimate, not a "
                 "fit, and not used). Other candidates: the drag coefficients measured for experiment 1 applied to a "
                 "different set-up, and the drive's actual speed history (Fig. 12 is a fit). ")
    text += (f"FFR gives {tf:.4f} m, {tf / ta:.2f} times ANCF (paper: {paper.TABLE5['ffr'][42] / paper.TABLE5['ancf'][56]:.2f} "
             "times): the paper's FFR has no geometric stiffening, so the centrifugal force cannot stiffen the beam "
             "against the drag. ")
    s = [r for r in t5["ffr_stiffened"] if r["tip_deflection_m"] is not None]
    if s:
        text += (f"With `geometric_stiffening = true`, FFR gives {s[0]['tip_deflection_m']:.4f} m "
                 f"({100 * (s[0]['tip_deflection_m'] / ta - 1):+.1f} % from ANCF). ")
    m = [r for r in t5.get("ffr_modal", []) if r["tip_deflection_m"] is not None]
    if m:
        text += (f"Reduced to its {m[0]['modes']} lowest modes (`modes = {m[0]['modes']}`, {m[0]['dof']} elastic "
                 f"coordinates with the stiffening's axial ones), it gives {m[0]['tip_deflection_m']:.4f} m "
                 f"({100 * (m[0]['tip_deflection_m'] / ta - 1):+.1f} % from ANCF). ")
    rows = [r for r in t6["rows"] if r["ffr_vs_ancf_pct"] is not None]
    big = [r for r in rows if abs(r["ffr_vs_ancf_pct"]) > 10.0]
    if big:
        text += (f"Table 6: FFR departs from ANCF by more than 10 % from omega_m/omega_1 = "
                 f"{big[0]['omega_m_over_omega_1']:.2f} (omega_m = {big[0]['omega_m']:.2f} rad/s) on; the paper puts the "
                 f"threshold at {paper.FFR_SPEED_LIMIT:.2f}.")
    return text


def t5_time(t5) -> float:
    return t5.get("time_s", 80.0)


def write(plan: Plan, outcomes, tables: dict, directory, quick: bool) -> Path:
    """Write figures, tables.json and report.md into ``directory``; returns the report's path."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    files = figures(plan, outcomes, tables, directory)
    (directory / "tables.json").write_text(json.dumps(tables, indent=1))
    failures = [o for o in outcomes.values() if o.failure]
    lines = ["# hubbeam: reproduction of the paper's Secs. 5 and 6", "",
             PROPERTIES_NOTE, "",
             f"Mode: {'quick' if quick else 'full'}. Experiment 1: {plan.exp1_time:g} s simulated, dt = 1 ms. "
             f"Experiment 2: {plan.exp2_time:g} s simulated, dt = {1000 * (plan.exp2_dt or 2e-3):g} ms. "
             f"{len(outcomes)} runs, {sum(o.wall_time_s for o in outcomes.values()):.0f} s of run time in all.", ""]
    if failures:
        lines += ["## Runs that failed", ""] + [f"- `{o.case.key}`: {o.failure}" for o in failures] + [""]
    lines += ["## Experiment 1 (Sec. 5): free hub, beam released under gravity", "",
              "### Table 2: first vibration frequency (FFT of the P1 strain)", ""] + _table2_md(tables["table2"])
    lines += ["", "### Table 3: thickness variants (finest meshes)", ""] + _table3_md(tables["table3"])
    lines += ["", _exp1_discussion(tables["table2"], tables["table3"], plan.exp1_time), ""]
    for fid in ("fig5_6", "fig7_8", "fig9_10"):
        if fid in files:
            lines += [f"![{fid}]({files[fid]})", ""]
    t_tip = t5_time(tables["table5"])
    t5_note = "" if t_tip == 80 else " (the paper: 80 s)"
    lines += [f"## Experiment 2 (Sec. 6): prescribed spin-up, tip deflection at {t_tip:g} s", "",
              f"### Table 5: tip deflection (tangential) at t = {t_tip:g} s" + t5_note, ""]
    lines += _table5_md(tables["table5"])
    lines += ["", "### Table 6: other drive speeds (the paper's values are not in its text)", ""]
    lines += _table6_md(tables["table6"])
    lines += ["", _exp2_discussion(tables["table5"], tables["table6"]), ""]
    for fid in ("fig12", "fig13", "table6", "table6_error"):
        if fid in files:
            lines += [f"![{fid}]({files[fid]})", ""]
    path = directory / "report.md"
    path.write_text("\n".join(lines) + "\n")
    return path
