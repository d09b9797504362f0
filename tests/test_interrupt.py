"""hubbeam.interrupt in process: a signal that lands while llvmlite (numba's code generator)
runs Python code is not raised there (llvmlite calls Python back from C, where an exception is
printed and lost) but shortly after, once the program is elsewhere."""

import os
import signal
import time

import pytest

from hubbeam import interrupt

pytestmark = pytest.mark.skipif(not hasattr(signal, "pthread_kill"), reason="needs pthread_kill")

# a function whose frame belongs to a module named like llvmlite's
_CODE_GENERATOR = {"__name__": "llvmlite.binding.stand_in", "os": os, "signal": signal, "time": time}
exec(
    "def busy_in_code_generator(seconds):\n"
    "    os.kill(os.getpid(), signal.SIGINT)\n"
    "    end = time.perf_counter() + seconds\n"
    "    while time.perf_counter() < end:\n"
    "        pass\n"
    "    return 'finished'\n",
    _CODE_GENERATOR,
)


@pytest.fixture(autouse=True)
def sigint_not_ignored():
    """A background job (CI's, or ``cmd &``) starts with SIGINT ignored, and handling() keeps an
    ignored signal ignored: give the test process Python's ordinary SIGINT handler."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_a_signal_inside_llvmlite_is_raised_after_it():
    finished = []
    with pytest.raises(interrupt.Interrupted) as info:
        with interrupt.handling():
            finished.append(_CODE_GENERATOR["busy_in_code_generator"](0.3))  # not raised inside
            end = time.perf_counter() + 5
            while time.perf_counter() < end:
                pass
    assert finished == ["finished"]
    assert info.value.signum == signal.SIGINT
    assert "busy_in_code_generator" not in {entry.name for entry in info.traceback}


def test_a_signal_elsewhere_is_raised_at_once():
    with pytest.raises(interrupt.Interrupted):
        with interrupt.handling():
            os.kill(os.getpid(), signal.SIGINT)
            end = time.perf_counter() + 5
            while time.perf_counter() < end:
                pass
