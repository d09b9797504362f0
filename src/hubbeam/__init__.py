"""hubbeam: rigid-flexible coupling dynamics of a rotating hub carrying a 3D flexible beam.

Plain-Python API::

    from hubbeam import load_scenario, static, modes
    sc = load_scenario("cantilever.toml", ["beam.elements=8"])
    print(modes(sc).to_dict()["frequencies_hz"])

``static``, ``modes``, ``run`` and ``build_system`` take a Scenario or the path of a
scenario file; anything else is a ScenarioError. The names are imported on first use, so
that ``import hubbeam`` (and the command line's start-up) stays fast.
"""

__all__ = ["load_scenario", "static", "modes", "run", "build_system", "ScenarioError"]
__version__ = "0.1.0"

_API = ("load_scenario", "static", "modes", "run", "build_system")


def __getattr__(name):
    if name in _API:
        from hubbeam import api

        return getattr(api, name)
    if name == "ScenarioError":
        from hubbeam.io.scenario import ScenarioError

        return ScenarioError
    raise AttributeError(f"module 'hubbeam' has no attribute {name!r}")


def __dir__():
    return sorted(list(globals()) + list(__all__))
