"""``hubbeam animate`` and ``vtk``: a run stored with ``--state`` drawn again."""

from __future__ import annotations

import math
import os

from hubbeam.cli.common import check_targets, say, write_jobs

def cmd_animate(args) -> dict:
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.state import read_state
    from hubbeam.io.targets import Target

    movie = os.path.splitext(args.output)[1].lower()
    if movie not in (".gif", ".mp4"):
        raise ScenarioError(f"-o {args.output}: the movie must be a .gif or an .mp4 file")
    if args.stride < 1:
        raise ScenarioError(f"--stride: must be >= 1 (got {args.stride})")
    if not (math.isfinite(args.fps) and 0.01 <= args.fps <= 100):
        raise ScenarioError(f"--fps: must be between 0.01 and 100 (got {args.fps:g})")
    from hubbeam.animate import COLORINGS, animate, camera, find_ffmpeg, frame_indices

    if args.color not in COLORINGS:
        raise ScenarioError(f"--color: unknown {args.color!r} (use {', '.join(COLORINGS)})")
    if not (math.isfinite(args.scale) and 0 < args.scale <= 1e6):
        raise ScenarioError(f"--scale: must be > 0 and at most 1e6 (got {args.scale:g})")
    try:
        view = camera(args.view)
    except ValueError as exc:
        raise ScenarioError(f"--view: {exc}") from None
    ffmpeg = find_ffmpeg() if movie == ".mp4" else None
    if movie == ".mp4" and ffmpeg is None:
        raise ScenarioError(f"-o {args.output}: an MP4 needs ffmpeg, which is not installed: pip install "
                            "'hubbeam[video]' (imageio-ffmpeg), or write a .gif")
    targets = check_targets([Target("-o", args.output)], args, ("result file", args.result))
    state = read_state(args.result, "result file")
    if state.partial:
        say(f"hubbeam: note: {args.result} holds a partial run: {state.partial}")
    frames = []
    write_jobs([(targets[0], lambda p: frames.append(animate(state, p, args.color, args.stride, args.fps, ffmpeg,
                                                             scale=args.scale, view=view)))],
           interruptible=True)  # rendering the frames is the computation: a signal stops it, nothing is written
    shown = 100.0 / int(int(1000 / args.fps) / 10)  # a GIF stores whole 1/100 s per frame (Pillow truncates)
    if movie == ".gif" and abs(shown - args.fps) > 0.01 * args.fps:
        say(f"hubbeam: note: --fps {args.fps:g}: a GIF stores each frame's time in whole 1/100 s, so it plays at "
             f"{shown:.4g} frames per second")
    if not args.json:
        drawn = state.times[frame_indices(state, args.stride)]
        span = f"t = {drawn[0]:g} s" if drawn.size == 1 else f"t = {drawn[0]:g} to {drawn[-1]:g} s"
        print(f"{frames[0]} frame{'' if frames[0] == 1 else 's'} ({span}) -> {args.output}")
    return {"frames": frames[0], "output": args.output}


def cmd_vtk(args) -> dict:
    import re
    from pathlib import Path

    from hubbeam.io import vtk
    from hubbeam.io.scenario import ScenarioError
    from hubbeam.io.state import read_state
    from hubbeam.io.targets import OutputError, Target

    check_targets([Target("-o", args.output, "directory")], args)
    state = read_state(args.result, "result file")
    if state.partial:
        say(f"hubbeam: note: {args.result} holds a partial run: {state.partial}")
    out = Path(args.output)
    pvd, vtus = vtk.file_names(state)
    body_vtus = vtk.body_file_names(state)
    pattern = re.compile(re.escape(vtk.series_name(state)) + rf"(_bodies)?_\d{{{vtk.INDEX_DIGITS}}}\.vtu")
    old = sorted(p for p in out.iterdir() if p.name == pvd or pattern.fullmatch(p.name)) if out.is_dir() else []
    if old and not args.force:
        raise ScenarioError(f"-o {out}: holds a series named {vtk.series_name(state)!r} already ({old[0].name}"
                            f"{f' and {len(old) - 1} more' if len(old) > 1 else ''}); give another directory or "
                            "--force to replace it")
    from hubbeam.io.targets import check_inside

    check_inside("-o", out, [pvd, *vtus, *body_vtus])
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / pvd).unlink(missing_ok=True)  # --force: an old collection must not list the new files mixed with old ones
    except OSError as exc:
        raise OutputError(f"-o {out}: cannot create the directory or remove the old {pvd} ({exc.strerror})") from None
    from hubbeam.io.bodies import rigid_bodies

    bodies = rigid_bodies(state)
    jobs = [job for i, (name, body_name) in enumerate(zip(vtus, body_vtus)) for job in (
        (Target("-o", str(out / name)), lambda p, i=i: vtk.write_vtu(state, i, p)),
        (Target("-o", str(out / body_name)), lambda p, i=i: vtk.write_bodies_vtu(state, bodies, i, p)))]
    from hubbeam import interrupt
    from hubbeam.io.targets import write_all

    def left(n):  # n files written: beams and bodies alternate
        return (f"{n // 2} of {len(vtus)} time steps: {out} holds " +
                (f"{vtus[0]} to {vtus[(n - 1) // 2]} (and their bodies' files) but no {pvd} (run again with --force for "
                 "the whole series)" if n else "none of them"))

    done = 0
    try:
        for start in range(0, len(jobs), 100):  # in chunks: a signal is noticed between them
            written, errors = write_all(jobs[start : start + 100])  # a signal in a chunk takes effect after it
            done += len(written)
            if errors:  # a full disk: the first reason, not one per file
                more = f" (and {len(errors) - 1} more files)" if len(errors) > 1 else ""
                raise OutputError(f"{errors[0]}{more}; after {left(done)}")
            interrupt.raise_pending()
    except interrupt.Interrupted as exc:
        exc.detail = f" after {left(done)}"
        raise
    # the collection last: it never lists a file that is not there
    write_jobs([(Target("-o", str(out / pvd)), lambda p: Path(p).write_text(vtk.pvd_text(state), encoding="utf-8"))])
    for stale in old:  # --force: files of an earlier, longer series
        if stale.name != pvd and stale.name not in vtus and stale.name not in body_vtus:
            stale.unlink(missing_ok=True)
    if not args.json:
        print(f"{len(vtus)} time steps, the beams and {len(bodies)} rigid bod{'y' if len(bodies) == 1 else 'ies'} "
              f"-> {out / pvd}")
    return {"files": len(vtus), "bodies": [b.name for b in bodies], "pvd": str(out / pvd)}


