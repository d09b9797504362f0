"""The ``hubbeam`` command line (see docs/scenario.md and docs/reliability.md).

Exit status: 0 success, 2 bad input (one line naming the key or option), 1 failed
computation or failed write (a line saying where and what to try; the results so far are
written), 128 + N when stopped by signal N (130 SIGINT, 143 SIGTERM, 129 SIGHUP; a run
writes its partial trajectory). Output targets are checked before any computation. No
traceback reaches the user unless the environment variable HUBBEAM_DEBUG is set.

Only the standard library is imported at module level: the signal handlers are in place
before numpy, numba or xarray load, so an early Ctrl-C is one line, not a traceback.
"""

from __future__ import annotations

import os
import sys

from hubbeam.cli.analysis import cmd_linearize, cmd_modes, cmd_static
from hubbeam.cli.common import compile_note, guarded_stdout, load, print_json, raised_in, say
from hubbeam.cli.parser import build_parser
from hubbeam.cli.run import cmd_run
from hubbeam.cli.studies import cmd_applicability, cmd_campbell, cmd_identify, cmd_reproduce, cmd_sweep
from hubbeam.cli.viewing import cmd_animate, cmd_vtk

#: names this module used to import at its top, still importable from it (loaded on first use)
_LAZY = {"EXAMPLES": "hubbeam.io.examples", "example_text": "hubbeam.io.examples",
         "load_scenario": "hubbeam.io.scenario", "ScenarioError": "hubbeam.errors",
         "ComputationError": "hubbeam.errors"}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        return getattr(importlib.import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'hubbeam.cli' has no attribute {name!r}")


# ------------------------------------------------------------------------------ main
def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit status. SIGINT, SIGTERM and SIGHUP are handled
    (see :mod:`hubbeam.interrupt`) from here on; the previous handlers come back after it.

    ``argv`` None: the command line of this process (the ``hubbeam`` script, ``python -m
    hubbeam.cli``), which ends after the command. The modules it loads make objects that live
    until the process ends, not garbage: the cyclic garbage collector is off while they load
    and they are then frozen out of it (:func:`gc.freeze`, in :func:`_settled`), and so is
    everything at the end. Otherwise its collections walked numba's and pydantic's objects
    again and again (about 0.2 s of ``hubbeam run benchmarks/case_a.toml`` during the
    command), and Python's last one at exit walked all of them (about 0.3 s after numba had
    loaded its compiled code). Called with a list (tests, scripts), the collector is left alone."""
    import gc

    from hubbeam import interrupt

    program = argv is None
    if program:
        gc.disable()  # until _settled
    try:
        with interrupt.handling(final=program):
            return _main(argv, program)
    except interrupt.Interrupted as exc:  # during start-up (imports), before _main could catch it
        say(f"hubbeam: interrupted by {exc.name}{exc.detail or '; nothing written'}")
        return exc.exit_code
    finally:
        if program:
            gc.freeze()  # the collection at exit then has nothing to walk


def _settled(program: bool) -> None:
    """The command's modules are loaded: in a process that ends after its command (see
    :func:`main`), the objects alive now move into the garbage collector's permanent
    generation and the collector is on again for what the computation makes."""
    if program:
        import gc

        gc.freeze()
        gc.enable()


def _main(argv, program: bool = False) -> int:
    """The command, with the warnings of the libraries it uses (numpy, scipy, matplotlib)
    caught: on success each distinct one is one ``hubbeam: warning:`` line; on failure the
    failure's one line says what matters (a warning is not printed with its source line)."""
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        code = _command(argv, program)
    if code == 0:
        for text in dict.fromkeys(f"{w.category.__name__}: {w.message} ({w.filename.rsplit(os.sep, 1)[-1]}:{w.lineno})"
                                  for w in caught):
            say(f"hubbeam: warning: {text}")
    return code


def _command(argv, program: bool = False) -> int:
    from hubbeam.interrupt import Interrupted, raise_pending

    args = build_parser().parse_args(argv)
    if sys.stdout is None:  # started with stdout closed (`hubbeam ... >&-`): what it prints would be lost
        say("hubbeam: cannot write results: stdout is closed, and the command prints its result or summary there; "
            "redirect it to a file (or to /dev/null to drop it)")
        return 1
    if args.command in ("example", "animate", "vtk"):
        _settled(program)  # these load their modules as they go (matplotlib, h5py)
    from hubbeam.errors import ComputationError, ScenarioError
    from hubbeam.io.examples import example_text
    from hubbeam.io.targets import OutputError

    stdout = sys.stdout
    sys.stdout = guarded_stdout(stdout)  # a failed write there (a full disk) is a failed write, named
    try:
        if args.command == "example":
            sys.stdout.write(example_text(args.name))
            sys.stdout.flush()
            return 0
        if args.command == "reproduce":
            compile_note()
            _settled(program)
            return cmd_reproduce(args)
        if args.command == "applicability":
            compile_note()
            _settled(program)
            result = cmd_applicability(args)
        elif args.command in ("animate", "vtk"):
            result = {"animate": cmd_animate, "vtk": cmd_vtk}[args.command](args)
        else:
            scenario = load(args)
            compile_note()  # imports the solver: numba, scipy.linalg and the model's modules
            _settled(program)
            handler = {"static": cmd_static, "modes": cmd_modes, "run": cmd_run, "campbell": cmd_campbell,
                       "linearize": cmd_linearize,
                       "sweep": cmd_sweep, "identify": cmd_identify}[args.command]
            result = handler(args, scenario)
        raise_pending()
        if args.json:
            print_json(result)
        sys.stdout.flush()  # here, where a failure is reported, not at exit
        return 0
    except ScenarioError as exc:
        say(f"hubbeam: error: {exc}")
        return 2
    except OutputError as exc:
        say(f"hubbeam: cannot write results: {exc}")
        return 1
    except ComputationError as exc:
        say(f"hubbeam: computation failed: {exc}")
        return 1
    except Interrupted as exc:
        say(f"hubbeam: interrupted by {exc.name}{exc.detail or '; nothing written'}")
        return exc.exit_code
    except KeyboardInterrupt:
        say("hubbeam: interrupted")
        return 130
    except BrokenPipeError:  # the reader went away (`hubbeam run ... | head`): stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())  # so that Python's final flush does not fail again
        return 0
    except ArithmeticError as exc:  # overflow, division by zero: a computation out of the range of doubles
        if os.environ.get("HUBBEAM_DEBUG"):
            raise
        say(f"hubbeam: computation failed: {exc.__class__.__name__} in {raised_in(exc)} ({exc}); the scenario's "
             "numbers are out of the range the computation can hold: check its values and units (SI)")
        return 1
    except MemoryError:
        say("hubbeam: computation failed: out of memory; try a coarser model (beam.elements), a larger "
             "analysis.output_dt or a shorter analysis.t_end")
        return 1
    except Exception as exc:  # the last line of defence: never a traceback for users
        if os.environ.get("HUBBEAM_DEBUG"):
            raise
        say(f"hubbeam: internal error: {exc.__class__.__name__}: {exc} (set HUBBEAM_DEBUG=1 for a traceback)")
        return 1
    finally:
        sys.stdout = stdout


if __name__ == "__main__":
    sys.exit(main())
