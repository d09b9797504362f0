"""The compiled generalized-alpha loop against the Python step, its chart changes, failures and output times."""

import numpy as np
import pytest

from hubbeam.elements.ancf.chart import frame_from_director
from hubbeam.io.scenario import Sensor
from hubbeam.simulation import initial_state, simulate
from hubbeam.solvers import generalized_alpha as ga
from hubbeam.solvers import newton_control as nc
from hubbeam.errors import ComputationError
from hubbeam.system.beam import AncfBeam
from hubbeam.system.laws import DriveProfile
from hubbeam.system.multibody import MultibodySystem, single_beam_system
from tests.conftest import assert_compiled_steps_are_python_steps, L, plate

TIP = Sensor(name="tip", kind="tip_deflection")


def spinning_beam():
    """A driven hub with a twisted, damped plate under gravity: every term of the equations is active."""
    return single_beam_system(AncfBeam(L, 3, plate()), radius=0.35, twist=np.pi / 4, motion="prescribed",
                         drive=DriveProfile("spin_up", 2.0, 1.0), gravity=np.array([0, -9.81, 0]),
                         tip_moment=np.array([0.0, 0.0, 0.05]), damping=(1.73, 1.4))


class PythonOnly(MultibodySystem):
    """The same system integrated step by step in Python."""

    compiled = False


@pytest.mark.parametrize("update", ["iteration", "step", "adaptive"])
def test_compiled_steps_are_the_python_steps(update):
    assert_compiled_steps_are_python_steps(spinning_beam(), update)


def test_a_chart_change_inside_the_compiled_run_matches_the_python_run():
    """A plate falling under gravity from a chart whose singular direction its tangents approach:
    both runs change the chart at the same step and end in the same state."""
    system = single_beam_system(AncfBeam(L, 4, plate()), radius=0.35, twist=np.pi / 2, gravity=np.array([0, -9.81, 0]))
    python = PythonOnly(system.beams, system.hub, system.gravity, system.damping)
    start = initial_state(system)
    F = frame_from_director(np.array([-0.3, 0.954, 0.0]))[None]  # 1 + d.tau = 0.7 when straight
    state = ga.init(system, system.remap(start.x, start.chart, F), F)
    runs = [simulate(s, [TIP], t_end=0.4, dt=1e-3, output_dt=0.1, state=state) for s in (system, python)]
    assert runs[0].chart_switches == runs[1].chart_switches >= 1
    tips = [np.array([list(r.values()) for r in t.records["tip"]]) for t in runs]
    assert np.max(np.abs(tips[0] - tips[1])) < 1e-9
    assert tips[0][-1, 1] < -0.05  # it did fall


def test_a_failed_compiled_run_reports_where_and_keeps_the_results():
    system = spinning_beam()
    with pytest.raises(ComputationError) as info:
        simulate(system, [TIP], t_end=0.1, dt=2e-3, output_dt=0.01,
                 newton=nc.NewtonOptions(max_iterations=1, tolerance=1e-15, update="iteration"))
    message = str(info.value)
    assert "Newton did not converge in 1 iterations" in message and "t = 0.002 s (step 1)" in message
    assert info.value.partial.times == [0.0] and info.value.partial.steps == 0


def test_output_times_are_multiples_of_the_output_step_and_the_end():
    system = spinning_beam()
    traj = simulate(system, [TIP], t_end=0.105, dt=5e-3, output_dt=0.02)
    assert traj.times == pytest.approx([0.0, 0.02, 0.04, 0.06, 0.08, 0.1, 0.105])
    assert traj.steps == 21 and traj.factorisations >= 1


def test_cache_is_cold_reads_numbas_cache_index(tmp_path, monkeypatch):
    """cache_is_cold (the CLI's note before the first compile): True before a cached function's
    first compile, False once its code is on disk (also for a fresh import, as in a new
    process), True again when its source changes."""
    import importlib
    import sys
    import time

    from hubbeam.solvers.compiled_alpha import advance, cache_is_cold

    source = tmp_path / "cold_probe.py"
    source.write_text("from numba import njit\n\n@njit(cache=True)\ndef f(x):\n    return x + 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    module = importlib.import_module("cold_probe")
    assert cache_is_cold(module.f)
    assert module.f(1) == 2
    assert not cache_is_cold(module.f)
    assert not cache_is_cold(importlib.reload(module).f)
    time.sleep(0.01)
    source.write_text("from numba import njit\n\n@njit(cache=True)\ndef f(x):\n    return x + 20\n")
    assert cache_is_cold(importlib.reload(module).f)
    sys.modules.pop("cold_probe", None)
    assert isinstance(cache_is_cold(), bool) and cache_is_cold() == cache_is_cold(advance)


STACK_SCRIPT = """
import resource, sys
from hubbeam import api, simulation as S
from hubbeam.io.scenario import load_example
scenario = load_example("exp1", [])
system = api.build_system(scenario, None)
state = S.initial_state(system)
params = S.ga.AlphaParameters.from_spectral_radius(0.8)
steps = S.CompiledSteps(system, params, S.nc.NewtonOptions(), 1e-3, state, S.record_needs(scenario.sensors, system))
state, done, its, limit, error, records = steps.advance(state, 5000, 0, 10, 5000)
print(done, error)
"""


def test_one_long_chunk_keeps_the_stack_flat(tmp_path):
    """5000 steps in one compiled call on a 1 MB stack: every step must give back the stack it
    takes (a function inlined into the loop with literal_unroll once grew it by ~1.3 kB a step, so
    a chunk of ~6000 steps overflowed the default 8 MB stack and a long run died of SIGSEGV)."""
    import resource
    import subprocess
    import sys

    def small_stack():
        resource.setrlimit(resource.RLIMIT_STACK, (1 << 20, 1 << 20))

    out = subprocess.run([sys.executable, "-c", STACK_SCRIPT], capture_output=True, text=True,
                         preexec_fn=small_stack, timeout=600)
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    assert out.stdout.split() == ["5000", "None"]
