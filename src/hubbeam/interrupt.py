"""Interruption of a command by SIGINT, SIGTERM or SIGHUP.

:func:`handling` (used by the command line around a whole command) turns these signals
into an :class:`Interrupted` exception raised where the program is, so every command stops
the same way: what it has is written where that is natural (``run`` writes its partial
trajectory), one line goes to stderr and the exit status is 128 + the signal number (130
for SIGINT, 143 for SIGTERM, 129 for SIGHUP). Compiled code cannot be interrupted, so the
time integration returns to Python at least every half second (see
:func:`hubbeam.simulation.simulate`).

Inside :func:`deferred` (writing results) a signal is only noted; it takes effect after the
block, so a result file is never left half written.

A signal that lands while llvmlite (numba's code generator) is in Python code is not raised
there either: llvmlite calls Python back from C, and an exception raised in such a callback is
printed and lost. The signal is sent again a moment later, until it lands elsewhere.
"""

from __future__ import annotations

import contextlib
import signal
import threading

#: seconds after which a signal that landed in llvmlite is sent again
RESEND_AFTER = 0.05

#: the signals that interrupt a command
SIGNALS = tuple(s for s in (getattr(signal, n, None) for n in ("SIGINT", "SIGTERM", "SIGHUP")) if s is not None)

_state = {"defer": 0, "pending": None, "received": None, "active": False}


class Interrupted(BaseException):
    """A command was stopped by a signal. A BaseException, like KeyboardInterrupt, so that
    ``except Exception`` clauses do not swallow it. ``partial`` holds results so far when
    the interrupted computation had any; ``detail`` what the command did about it."""

    def __init__(self, signum: int):
        self.signum = int(signum)
        try:
            self.name = signal.Signals(self.signum).name
        except ValueError:
            self.name = f"signal {self.signum}"
        super().__init__(f"interrupted by {self.name}")
        self.partial = None
        self.detail = ""

    @property
    def exit_code(self) -> int:
        return 128 + self.signum


def _handler(signum, frame):
    _state["received"] = signum
    if _state["defer"]:
        if _state["pending"] is None:
            _state["pending"] = signum
        return
    if hasattr(signal, "pthread_kill") and _in_code_generator(frame):
        _resend_later(signum)
        return
    raise Interrupted(signum)


def _in_code_generator(frame) -> bool:
    """Whether ``frame`` or a caller of it is llvmlite's (whose C code calls Python back)."""
    while frame is not None:
        if str(frame.f_globals.get("__name__", "")).startswith("llvmlite"):
            return True
        frame = frame.f_back
    return False


def _resend_later(signum: int) -> None:
    """Send ``signum`` to the main thread again after :data:`RESEND_AFTER` seconds."""
    target = threading.main_thread().ident

    def resend():
        if _state["active"]:  # not once the command has ended and the old handlers are back
            with contextlib.suppress(OSError, ValueError):
                signal.pthread_kill(target, signum)

    timer = threading.Timer(RESEND_AFTER, resend)
    timer.daemon = True
    timer.start()


def _final_handler(signum, frame):
    """After the last command of a process (:func:`handling` with ``final``): one line, and the
    process ends with 128 + N at once (not the default action, which ends it without a word)."""
    import os
    import sys

    try:
        name = signal.Signals(signum).name
    except ValueError:
        name = f"signal {signum}"
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    with contextlib.suppress(OSError):
        os.write(2, f"hubbeam: interrupted by {name} after the command had finished (its results are complete)\n"
                 .encode())
    os._exit(128 + signum)


@contextlib.contextmanager
def handling(final: bool = False):
    """Within the block SIGINT, SIGTERM and SIGHUP raise :class:`Interrupted`; the previous
    handlers come back after it, or, with ``final`` (the command line, whose process ends after
    the block), a handler that says one line and ends the process with 128 + N, so that a
    signal in its last moments is not the default action's silent end. A signal that was
    ignored when the program started stays ignored (``nohup`` ignores SIGHUP, a shell's
    background job SIGINT). Does nothing outside the main thread."""
    previous = {}
    try:
        for s in SIGNALS:
            try:
                if signal.getsignal(s) is signal.SIG_IGN:
                    continue
                previous[s] = signal.signal(s, _handler)
            except (ValueError, OSError):  # not the main thread, or not settable here
                pass
    except BaseException:
        _restore(previous)
        raise
    _state["pending"] = _state["received"] = None
    _state["active"] = bool(previous)
    try:
        yield
    finally:
        _state["active"] = False
        _restore({s: _final_handler for s in previous} if final else previous)
        _state["pending"] = _state["received"] = None


def check() -> None:
    """Raise :class:`Interrupted` again if a signal came and its exception was swallowed on
    the way (a bare ``except:`` in some library): called between chunks of work."""
    if _state["received"] is not None and not _state["defer"]:
        raise Interrupted(_state["received"])


def _restore(previous: dict) -> None:
    for s, h in previous.items():
        with contextlib.suppress(ValueError, OSError, TypeError):
            signal.signal(s, h)


@contextlib.contextmanager
def deferred():
    """Signals within the block are held, not raised: :func:`raise_pending` (or
    :func:`take_pending`) deals with them after it."""
    _state["defer"] += 1
    try:
        yield
    finally:
        _state["defer"] -= 1


def take_pending() -> int | None:
    """The signal held by :func:`deferred`, if any (and forget it)."""
    signum, _state["pending"] = _state["pending"], None
    return signum


def raise_pending(detail: str = " after the results were written") -> None:
    """Raise :class:`Interrupted` for a signal held by :func:`deferred`, if there is one."""
    if not _state["defer"]:
        signum = take_pending()
        if signum is not None:
            exc = Interrupted(signum)
            exc.detail = detail
            raise exc


@contextlib.contextmanager
def children_spared():
    """Processes (and threads) started within the block have SIGINT blocked: a Ctrl-C, which a
    terminal sends to the whole process group, then reaches only this process, which stops
    them, instead of making every worker print a traceback. A SIGINT that arrives within the
    block is delivered when it ends."""
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)
