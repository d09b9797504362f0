"""The figures of docs/modes.md: `python docs/figures/modes.py`.

Draws docs/figures/modes_cantilever.png (`hubbeam modes` on the bundled cantilever) and
docs/figures/campbell_crossing.png (`hubbeam campbell` on a near-square blade whose flap and
lag branches cross), through the command line.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from hubbeam.cli import main
from hubbeam.io.scenario import example_text

OUT = Path(__file__).resolve().parent

CROSSING = """name = "crossing"
[beam]
formulation = "ancf"
elements = 4
length = 1.0
width = 0.011
thickness = 0.010
density = 2700.0
youngs_modulus = 70.0e9
poisson_ratio = 0.33
[hub]
motion = "fixed"
radius = 0.0
twist = 90.0
[environment]
gravity = [0.0, 0.0, 0.0]
"""

if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as tmp:
        cantilever, crossing = Path(tmp) / "cantilever.toml", Path(tmp) / "crossing.toml"
        cantilever.write_text(example_text("cantilever"))
        crossing.write_text(CROSSING)
        for argv in (["modes", str(cantilever), "--plot", str(OUT / "modes_cantilever.png")],
                     ["campbell", str(crossing), "--omega", "0:50:11", "--count", "4", "-o",
                      str(OUT / "campbell_crossing.png")]):
            if main(argv):
                sys.exit(f"hubbeam {' '.join(argv)} failed")
