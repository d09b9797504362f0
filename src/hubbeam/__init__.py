"""hubbeam: rigid-flexible coupling dynamics of a rotating hub carrying a 3D flexible beam.

Plain-Python API::

    from hubbeam import load_scenario, static, modes
    sc = load_scenario("cantilever.toml", ["beam.elements=8"])
    print(modes(sc).to_dict()["frequencies_hz"])
"""

from hubbeam.api import build_system, modes, static
from hubbeam.io.scenario import ScenarioError, load_scenario

__all__ = ["load_scenario", "static", "modes", "build_system", "ScenarioError"]
__version__ = "0.1.0"
