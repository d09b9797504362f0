"""The figure and numbers of docs/state_space.md: `python docs/figures/state_space.py`.

The bundled spacecraft (PD slew law in the loop, no damping but the law's) with its panels on
8 ANCF elements each: the full state space (266 states) against its modal truncation to the
5 lowest modes the hub torque reaches (10 states), a balanced reduction to 6 states, and the
panels as FFR beams on 4 modes each (18 states), from hub torque to the hub angle and to the
root strain of panel a. Draws docs/figures/state_space_spacecraft.png and prints the sizes,
DC gains, the lowest poles, the Hankel singular values, the H-infinity bound and error, and
the time of the frequency responses (the same as `hubbeam linearize ... --json` prints).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.plots import style

OUT = Path(__file__).resolve().parent
OUTPUTS = ["theta", "root_strain_a"]
EIGHT = ["beams[*].elements=8"]
FFR4 = ['beams[*].formulation="ffr"', "beams[*].modes=4"]


def main() -> None:
    full = api.linearize(load_example("spacecraft", EIGHT), outputs=OUTPUTS)
    modal = full.reduced(5)
    balanced = full.balanced(6)
    ffr = api.linearize(load_example("spacecraft", FFR4), outputs=OUTPUTS)
    models = {"full, 266 states": full, "modal, 5 modes (10 states)": modal, "balanced, 6 states": balanced,
              "panels FFR on 4 modes (18 states)": ffr}
    f = np.logspace(-3, 3, 3000)
    start = time.perf_counter()
    responses = {name: m.frequency_response(f) for name, m in models.items()}
    print(f"frequency responses at {f.size} frequencies of the 4 models: {time.perf_counter() - start:.2f} s")
    for name, m in models.items():
        dc = m.dc_gain()[:, 0]
        low = ", ".join(f"{v:.6g}" for v in m.modal_summary()[0][:5])
        print(f"{name}: {m.A.shape[0]} states; DC gain theta {dc[0]:.9g} rad/(N m), strain {dc[1]:.3g} /(N m); "
              f"lowest modes {low} Hz")
    sigma = balanced.reduction["hankel_singular_values"]
    stable = np.abs(full.eigenvalues()) / (2 * np.pi)
    grid = np.unique(np.concatenate([f, stable[(stable > 1e-3) & (stable < 3e4)]]))
    error = np.max(np.linalg.norm(full.frequency_response(grid) - balanced.frequency_response(grid), ord=2, axis=(1, 2)))
    print(f"Hankel singular values: {', '.join(f'{v:.4g}' for v in sigma[:8])} ... ({len(sigma)}); "
          f"bound 2 sum(discarded) = {balanced.reduction['error_bound']:.4g}; largest error found {error:.4g}")
    with style.paper_style():
        fig, axes = style.figure(2, 2, height=5.6)
        for ax, row, (name, unit, factor) in zip(axes[0], range(2), [("hub angle", "rad/(N m)", 1.0),
                                                                     ("root strain of panel a", "\u00b5\u03b5/(N m)",
                                                                      1e6)]):
            for k, (label, G) in enumerate(responses.items()):
                ax.loglog(f, factor * np.abs(G[:, row, 0]), label=label, **style.styled(k))
            ax.set_xlabel("frequency (Hz)")
            ax.set_ylabel(style.axis_label("gain", unit))
            ax.set_title(f"hub torque \u2192 {name}")
        ax = axes[1, 0]
        for k, (label, m) in enumerate(models.items()):
            s = m.eigenvalues()
            s = s[(s.imag >= 0) & (np.abs(s) < 2 * np.pi * 30)]
            ax.plot(s.real, s.imag / (2 * np.pi), "xo+."[k], color=f"C{k}", ms=8 - 1.5 * k, label=label,
                    linestyle="none", mfc="none" if k == 1 else None)
        ax.set_xlabel("Re \u03bb (1/s)")
        ax.set_ylabel("Im \u03bb / 2\u03c0 (Hz)")
        ax.set_title("poles below 30 Hz")
        ax = axes[1, 1]
        for k, (label, m) in list(enumerate(models.items()))[1:3]:
            gap = np.linalg.norm(responses["full, 266 states"] - responses[label], ord=2, axis=(1, 2))
            ax.loglog(f, gap, label=label, **style.styled(k))
        ax.axhline(balanced.reduction["error_bound"], color="C2", lw=0.8, ls=":",
                   label="balanced: 2 \u03a3 discarded \u03c3")
        ax.set_xlabel("frequency (Hz)")
        ax.set_ylabel("error (largest singular value)")
        ax.set_title("|G full \u2212 G reduced|")
        ax.legend(loc="lower right")
        axes[0, 0].legend(loc="lower left")
        style.finish(fig, OUT / "state_space_spacecraft.png", "spacecraft: the full and the reduced state spaces",
                     "panels on 8 ANCF elements, PD law in the loop")

if __name__ == "__main__":
    main()
