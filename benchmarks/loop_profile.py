"""Where a compiled time step's process time goes, function by function, with Linux ``perf``.

    perf record -N -o /tmp/hinge.data python benchmarks/loop_profile.py run modal_hinge /tmp/hinge.data [REPS]
    python benchmarks/loop_profile.py report /tmp/hinge.data

``run`` builds one model (:data:`MODELS`: exp1, 10 s at 1 ms, FFR on 4 modes or nodal, clamped or
on case J's stiff flap hinge), loads the compiled loop from numba's cache and runs it REPS times
(default 10) for 10 000 steps, printing the process time per step. numba's code has no symbols
that ``perf`` can see, so at the end ``run`` writes ``/tmp/perf-PID.map`` (the map ``perf
report`` reads for code generated at run time): the address and size of every function in the
object code numba loaded from its cache (or compiled) for the dispatchers of hubbeam's modules.
It also keeps the loop's own object code (:func:`hubbeam.solvers.compiled_alpha.advance`) and
its load address next to the data file (``DATA.advance.o``, ``DATA.json``).

``report`` attributes the samples: the JIT code's share of the process, each named function's
share of the JIT code and its us per step (the JIT share times the measured time per step; the
samples taken outside the timed runs, while loading, are in the process total, not in the JIT
code), and, within the loop's own code, the samples on argument passing: stack stores and loads
and pushes, what a call copies into its arguments (numba passes a tuple of arrays field by
field: some 550 words per call of the equations on exp1 while the loop passed them the model
itself; 0.56 us per step on 4 modes, none since it passes a reference,
:mod:`hubbeam.system.by_reference`), grouped by the call whose argument block (``sub $N,
%rsp``) they fall in.

Needs ``perf`` (user-space sampling, ``perf_event_paranoid`` <= 2) and binutils (``nm``,
``objdump``); numba's cache must be warm (run the model once first). ``-N``: perf keeps no copies of
the binaries in ``~/.debug``. The map files stay in /tmp for later reports. Not part of the test suite.
"""

from __future__ import annotations

import bisect
import collections
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import numba.core.codegen as codegen

#: exp1 variants: (label, overrides)
MODELS = {
    "modal": ['beam.formulation="ffr"', "beam.modes=4"],
    "modal_hinge": ['beam.formulation="ffr"', "beam.modes=4", "HINGE"],
    "nodal": ['beam.formulation="ffr"'],
    "nodal_hinge": ['beam.formulation="ffr"', "HINGE"],
}

_set_object = codegen.CodeLibrary._set_compiled_object
#: every library numba loaded from its cache in this process, with its object code
_LOADED: list = []


def _keep_object(library, value):
    """numba drops a library's object code once it is loaded: keep a copy for the map."""
    _LOADED.append((library, value))
    return _set_object(library, value)


codegen.CodeLibrary._set_compiled_object = _keep_object  # before anything loads from the cache


def _functions(obj: bytes) -> tuple[list[tuple[int, int, str, str]], int]:
    """((offset in the code section, size, nm type, name) of the named functions in an ELF
    object, the code section's size)."""
    with tempfile.NamedTemporaryFile(suffix=".o", delete=False) as f:
        f.write(obj)
    symbols = subprocess.run(["nm", "-S", "--defined-only", f.name], capture_output=True, text=True,
                             check=True).stdout
    sections = subprocess.run(["objdump", "-h", f.name], capture_output=True, text=True, check=True).stdout
    os.unlink(f.name)
    rows = []
    for line in symbols.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "Tt":
            rows.append((int(parts[0], 16), int(parts[1], 16), parts[2], parts[3]))
    size = max((int(m.group(1), 16) for m in re.finditer(r"^\s*\d+\s+\.l?text\S*\s+([0-9a-f]+)", sections, re.M)),
               default=0)
    return rows, size


def _gaps(rows, size, owner):
    """Map entries for the code between the named functions: the callees numba linked into
    ``owner``'s object (private functions have no symbol), named after it."""
    out, end = [], 0
    for off, length, _, _ in sorted(rows):
        if off > end:
            out.append((end, off - end, f"{owner}.linked_callees"))
        end = max(end, off + length)
    if size > end:
        out.append((end, size - end, f"{owner}.linked_callees"))
    return out


def write_map(prefix: str) -> tuple[int, int | None]:
    """Write /tmp/perf-PID.map for every function numba loaded from its cache; keep
    advance's object code and load address under ``prefix``. Returns the functions mapped."""
    from numba.core.registry import cpu_target

    engine = cpu_target.target_context.codegen()._engine._ee
    lines, loop = [], None
    for library, obj in _LOADED:
        rows, section = _functions(obj)
        base = next((engine.get_function_address(n) - off for off, _, kind, n in rows
                     if kind == "T" and engine.get_function_address(n)), None)
        if base is None:
            continue
        lines += [f"{base + off:x} {size:x} {n}" for off, size, _, n in rows]
        main = max(rows, key=lambda r: r[1])[3]  # the library's own function: its largest
        lines += [f"{base + off:x} {size:x} {n}" for off, size, n in _gaps(rows, section, main)]
        if any("compiled_alpha7advance" in n for _, _, _, n in rows):
            loop = (obj, base)
    with open(f"/tmp/perf-{os.getpid()}.map", "w") as f:
        f.write("\n".join(lines) + "\n")
    if loop is not None:
        with open(prefix + ".advance.o", "wb") as f:
            f.write(loop[0])
    return len(lines), (loop[1] if loop else None)


def run(label: str, reps: int, prefix: str) -> None:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from engines import HINGE

    from hubbeam import api
    from hubbeam.io.scenario import load_example
    from hubbeam.simulation import CompiledSteps, initial_state
    from hubbeam.solvers import generalized_alpha as ga
    from hubbeam.solvers import newton_control as nc

    system = api.build_system(load_example("exp1", [HINGE if o == "HINGE" else o for o in MODELS[label]]))
    state, p = initial_state(system), ga.AlphaParameters.from_spectral_radius(0.8)
    times = []
    for _ in range(reps):
        loop = CompiledSteps(system, p, nc.NewtonOptions(), 1e-3, state)
        t = time.process_time()
        _, n, its, _, err, _ = loop.advance(state, 10000, 0, 10, 10000)
        if err is not None:
            raise err
        times.append(1e6 * (time.process_time() - t) / n)
    per_step = sorted(times)[len(times) // 2]
    mapped, base = write_map(prefix)
    with open(prefix + ".json", "w") as f:
        json.dump({"model": label, "pid": os.getpid(), "us_per_step": per_step, "steps": 10000 * reps,
                   "advance_base": base}, f)
    print(f"{label}: {per_step:.2f} us/step (median of {reps}; {min(times):.2f}-{max(times):.2f}), "
          f"Newton {its / n:.4f}; {mapped} functions mapped", flush=True)


def _short(symbol: str) -> str:
    """module.function of a numba symbol (_ZN, then <length><name> for each dotted part)."""
    if not symbol.startswith("_ZN"):
        return symbol[:40]
    rest, names = symbol[3:], []
    while rest and rest[0].isdigit():
        digits = re.match(r"\d+", rest).group(0)
        k = int(digits)
        names.append(rest[len(digits):len(digits) + k])
        rest = rest[len(digits) + k:]
    return ".".join(names[-2:])


def report(data: str) -> None:
    with open(data + ".json") as f:
        meta = json.load(f)
    script = subprocess.run(["perf", "script", "-i", data, "-F", "ip,sym,dso"], capture_output=True, text=True,
                            check=True).stdout
    total, jit = 0, []
    for line in script.splitlines():
        ip, _, rest = line.strip().partition(" ")
        sym, _, dso = rest.rpartition(" (")
        total += 1
        if dso.startswith("/tmp/perf-"):  # code generated at run time (numba's)
            jit.append((int(ip, 16), sym.strip()))
    by = collections.Counter(_short(sym) + (" (its linked callees)" if sym.endswith(".linked_callees") else "")
                             if sym.startswith("_ZN") else "(not mapped)" for _, sym in jit)
    per_jit = meta["us_per_step"] / max(len(jit), 1)
    print(f"{meta['model']}: {meta['us_per_step']:.2f} us/step; {total} samples, JIT code {len(jit)} "
          f"({100 * len(jit) / total:.1f} %); us per step by function (JIT share x time per step):")
    for name, n in by.most_common(12):
        print(f"  {n * per_jit:6.3f}  {name}")
    base = meta.get("advance_base")
    if base is None or not os.path.exists(data + ".advance.o"):
        return
    dis = subprocess.run(["objdump", "-dr", "--no-show-raw-insn", data + ".advance.o"], capture_output=True,
                         text=True, check=True).stdout
    ins, callee = [], {}
    for line in dis.splitlines():
        m = re.match(r"\s+([0-9a-f]+):\s+(.*)$", line)
        if "R_X86_64_64" in line:
            if ins:
                callee.setdefault(len(ins) - 1, _short(line.split()[-1]))
        elif m:
            ins.append((int(m.group(1), 16), m.group(2)))
    offsets = [o for o, _ in ins]
    starts = [i for i, (o, t) in enumerate(ins) if re.match(r"sub\s+\$0x[0-9a-f]{3,},%rsp", t)]
    blocks = [ins[i][0] for i in starts]
    # each argument block's callee: the first function address loaded after it
    names = {ins[i][0]: next((callee[j] for j in range(i, len(ins)) if j in callee), "?") for i in starts}
    stack = re.compile(r"(push|(v?mov\w*)\s+(\S*\(%rsp\),|%\w+,\S*\(%rsp\)))")
    own = [ip - base for ip, sym in jit if "compiled_alpha7advance" in sym and not sym.endswith(".linked_callees")]
    moves, per_block = 0, collections.Counter()
    for s in own:
        i = bisect.bisect_right(offsets, s) - 1
        if i >= 0 and stack.match(ins[i][1]):
            moves += 1
            j = bisect.bisect_right(blocks, s) - 1
            per_block[f"{names[blocks[j]]} at {blocks[j]:#x}" if j >= 0 else "-"] += 1
    print(f"the loop's own code (advance, without its linked callees): {len(own) * per_jit:.3f} us/step, of which "
          f"argument passing (stack moves and pushes) {moves * per_jit:.3f}; by the call whose arguments: "
          + ", ".join(f"{k} {n * per_jit:.3f}" for k, n in per_block.most_common(6)))


def main() -> None:
    what = sys.argv[1] if len(sys.argv) > 1 else "report"
    if what == "run":
        run(sys.argv[2], int(sys.argv[4]) if len(sys.argv) > 4 else 10, sys.argv[3])
    else:
        report(sys.argv[2] if len(sys.argv) > 2 else "perf.data")


if __name__ == "__main__":
    main()
