"""Where the first run's compile time goes: numba's typing and lowering against LLVM.

    python benchmarks/compile_time.py [EXAMPLE] [KEY=VALUE ...]   # default: exp1, about 85 s of CPU on a 2-core machine

    python benchmarks/compile_time.py exp1 then rotor3 [then EXAMPLE [KEY=VALUE ...] ...]

Runs the bundled example (default ``exp1``) for one output step in this process, with numba's
on-disk cache pointed at a new empty directory so that everything compiles, and prints

- the compile time (CPU seconds of this process, the steady number beside other jobs) of each
  compiled function (numba's ``numba:compile`` events): its own
  (``self``: typing, lowering and LLVM for its own module) and with what it compiled on the way
  (``total``), the largest first, and the functions the run called from Python;
- LLVM's share: optimising each function as it is lowered, optimising each function's module
  again after its callees' modules are linked into it, and making that module's machine code;
  with the modules that hold the most functions (numba links a copy of every callee's module
  into its caller's and finalises each module to machine code), and how many functions were
  made machine code in all (counting a function once in every module that holds it: a number
  of the code, not of the machine's load, to compare two versions on a busy machine).

Each ``then EXAMPLE`` runs one more example in the same process afterwards and prints what it
compiled on top (CPU seconds, compiles, its largest functions by their own time): the cost of
one more *model* whose kinds are already compiled. numba compiles the system's equations, the
time loop, the step's powers and the records once per model type (the tuple of the kinds'
packs a system holds), and each of these links its callees' modules into its own and optimises
and makes machine code of the whole again; that, not the kinds, is what every further model
of a test run or a session pays.

The LLVM parts are timed by wrapping three methods of numba's ``JITCodeLibrary``
(``add_llvm_module``, ``_optimize_final_module``, ``_finalize_specific``): numba internals,
checked for numba 0.68; if they are missing, the script says so and prints the first part
only. Not a test: timings do not belong in tests.
"""

from __future__ import annotations

import collections
import os
import sys
import tempfile
import time


def run_recorded(example: str, overrides: list[str]):
    """Run ``example`` for one output step (unless ``analysis.t_end`` is given) with numba's compile
    events recorded in CPU time (numba's own ``install_recorder`` stamps wall time): the events
    as (CPU seconds, event), and the process's CPU and wall seconds of the run."""
    from numba.core import event

    class CpuRecorder(event.Listener):
        def __init__(self):
            self.buffer = []

        def on_start(self, ev):
            self.buffer.append((time.process_time(), ev))

        def on_end(self, ev):
            self.buffer.append((time.process_time(), ev))

    recorder = CpuRecorder()
    start_cpu, start_wall = time.process_time(), time.perf_counter()
    with event.install_listener("numba:compile", recorder):
        from hubbeam import api
        from hubbeam.io.scenario import load_example

        scenario = load_example(example, overrides)
        if not any(o.split("=", 1)[0].strip() == "analysis.t_end" for o in overrides):  # one output step is enough
            scenario = load_example(example, overrides + [f"analysis.t_end={scenario.output_dt}"])
        api.run(scenario)
    return recorder.buffer, time.process_time() - start_cpu, time.perf_counter() - start_wall


def compile_spans(buffer):
    """Each compile as (function, start, end, depth) from the recorded events, and per function
    its own seconds (without what it compiled on the way), its total and its number of compiles."""
    stack, spans = [], []
    for stamp, ev in buffer:
        if ev.is_start:
            dispatcher = ev.data.get("dispatcher")
            stack.append((dispatcher.py_func.__qualname__ if dispatcher is not None else str(ev.data.get("args")),
                          stamp))
        else:
            name, begun = stack.pop()
            spans.append((name, begun, stamp, len(stack)))
    own, total, count = collections.Counter(), collections.Counter(), collections.Counter()
    for name, a, b, depth in spans:
        children = sum(b2 - a2 for _, a2, b2, d2 in spans if d2 == depth + 1 and a2 >= a and b2 <= b)
        own[name] += b - a - children
        total[name] += b - a
        count[name] += 1
    return spans, own, total, count


def example_and_overrides(words: list[str]) -> tuple[str, list[str]]:
    """The example named in ``words`` (default exp1) and its KEY=VALUE overrides."""
    return (words[0] if words and "=" not in words[0] else "exp1"), [w for w in words if "=" in w]


def print_largest(own, total, count, n: int) -> None:
    """The ``n`` functions that took the most compile time of their own (CPU s)."""
    print(f"{'self s':>7} {'total s':>8}  function (the {n} largest)")
    for name, seconds in own.most_common(n):
        print(f"{seconds:7.2f} {total[name]:8.2f}  {name}" + (f" x{count[name]}" if count[name] > 1 else ""))


def main(argv: list[str]) -> None:
    groups = [[]]
    for a in argv:
        if a == "then":
            groups.append([])
        else:
            groups[-1].append(a)
    example, overrides = example_and_overrides(groups[0])
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="hubbeam-compile-")
    from numba.core import codegen

    llvm = collections.defaultdict(lambda: [0.0, 0.0, 0.0, 0])  # module: function opt, module opt, machine code, fns
    # functions made machine code, summed over every module finalised (the 'then' reports' count;
    # the first report's counts each module name once, as the numbers quoted in docs/benchmarks.md)
    made = [0]
    library = getattr(codegen, "JITCodeLibrary", None)
    parts = ("add_llvm_module", "_optimize_final_module", "_finalize_specific")
    wrapped = library is not None and all(hasattr(library, p) for p in parts)

    def timed(slot, method):
        def wrapper(self, *args):
            start = time.process_time()
            out = method(self, *args)
            llvm[self.name][slot] += time.process_time() - start
            if slot == 2:
                llvm[self.name][3] = sum(1 for f in self._final_module.functions if not f.is_declaration)
                made[0] += llvm[self.name][3]  # every module, also one of a name seen before
            return out
        return wrapper

    if wrapped:
        for slot, name in enumerate(parts):
            setattr(library, name, timed(slot, getattr(library, name)))
    else:
        print("numba's JITCodeLibrary has changed: LLVM's share is not timed")

    buffer, cpu, wall = run_recorded(example, overrides)
    spans, own, total, count = compile_spans(buffer)
    compiled = sum(b - a for _, a, b, depth in spans if depth == 0)
    print(f"{example} {' '.join(overrides)}: process {wall:.1f} s wall, {cpu:.1f} s CPU; compiling {compiled:.1f} s "
          f"of CPU in {len(own)} compiled functions")
    print()
    print_largest(own, total, count, 25)
    again = [f"{name} x{n} ({own[name]:.1f} s)" for name, n in count.most_common() if n > 1]
    print("\ncompiled more than once (one per signature): " + (", ".join(again) or "none"))
    print("\ncalled from Python: " + ", ".join(f"{name} {b - a:.1f} s" for name, a, b, depth in
                                               sorted(spans, key=lambda s: s[1]) if depth == 0))
    if wrapped:
        sums = [sum(v[i] for v in llvm.values()) for i in range(3)]
        print(f"\nLLVM {sum(sums):.1f} s in {len(llvm)} modules: optimising each function {sums[0]:.1f} s, "
              f"each module with its callees linked in {sums[1]:.1f} s, machine code {sums[2]:.1f} s")
        print(f"functions made machine code: {sum(v[3] for v in llvm.values())} (a function once per module that "
              f"links it in; a count that does not move with the machine's load)")
        print(f"{'functions':>9} {'module opt s':>12} {'machine s':>9}  module (the 8 largest)")
        for name, (_, opt, code, functions) in sorted(llvm.items(), key=lambda kv: -kv[1][3])[:8]:
            print(f"{functions:9d} {opt:12.2f} {code:9.2f}  {name}")
    for group in groups[1:]:
        before = [sum(v[i] for v in llvm.values()) for i in range(3)] + [made[0]]
        buffer, cpu, wall = run_recorded(*example_and_overrides(group))
        spans, own, total, count = compile_spans(buffer)
        after = [sum(v[i] for v in llvm.values()) for i in range(3)] + [made[0]]
        share = (f"; LLVM {sum(after[:3]) - sum(before[:3]):.1f} s (module with its callees linked in "
                 f"{after[1] - before[1]:.1f} s, machine code {after[2] - before[2]:.1f} s), "
                 f"{after[3] - before[3]} functions made machine code" if wrapped else "")
        print(f"\nthen {' '.join(group)}: {cpu:.1f} s CPU ({wall:.1f} s wall), {len(spans)} compiles{share}")
        print_largest(own, total, count, 12)


if __name__ == "__main__":
    main(sys.argv[1:])
