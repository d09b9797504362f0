"""The hub and its beams in 3D over a run (matplotlib animation, Agg). Numerics never import this module.

Input: a run's recorded state (:class:`hubbeam.io.state.RunState`). Each beam is drawn as a
ribbon, its centre line -+ (b/2) m at every stored station (b the station's width, m the
section's unit vector along it), so twist and bending of the sections show; the hub is a
disc of the hub radius (the largest root radius) in the plane normal to j0, with a spoke
along i_h(theta) that turns with it; a hinge (a beam's root on a revolute joint) is a black
dot at the beam's root. Axes: global x, -z and y (so the hub axis j0 points
up and the view stays right-handed), the same limits in every frame (the whole run's
extent) and equal scales. One frame per stored output time, or every ``stride``-th.
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from hubbeam.io.state import RunState  # noqa: E402

#: sides of the polygon drawn as the hub
HUB_SIDES = 36


@dataclass(frozen=True)
class Coloring:
    """A quantity to colour the ribbons by: ``label`` (with units) and ``values(state, k)``
    giving beam k's (nt, n) values at its stations, or None for a plain colour."""

    label: str
    values: object


#: --color choices: the upper surface's axial strain, the deflection's magnitude, or one colour
COLORINGS = {
    "strain": Coloring("upper-surface axial strain", lambda state, k: state.beams[k].surface_strain),
    "deflection": Coloring("deflection (m)",
                           lambda state, k: np.linalg.norm(state.displacement(k), axis=2)),
    "none": Coloring("", None),
}


def _view(points: np.ndarray) -> np.ndarray:
    """Global (x, y, z) -> plot (x, -z, y): j0 up, right-handed."""
    p = np.asarray(points)
    return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)


def ribbon_quads(state: RunState, k: int, i: int) -> np.ndarray:
    """Beam k's ribbon at output time i: (n - 1, 4, 3) quadrilaterals, global coordinates (m)."""
    beam = state.beams[k]
    half = 0.5 * beam.width[:, None] * beam.m[i]
    left, right = beam.centre_line[i] - half, beam.centre_line[i] + half
    return np.stack([left[:-1], right[:-1], right[1:], left[1:]], axis=1)


def hub_polygon(state: RunState, i: int) -> np.ndarray:
    """The hub disc at output time i: (HUB_SIDES, 3) points (m), in the plane of the hub's frame
    normal to its axis, turned with it (the base's motion and the hub angle)."""
    radius = state.hub_radius if state.hub_radius > 0 else 0.05 * _extent(state)
    phi = 2 * np.pi * np.arange(HUB_SIDES) / HUB_SIDES
    disc = radius * np.column_stack([np.cos(phi), np.zeros(HUB_SIDES), np.sin(phi)])
    return state.hub_origin[i] + disc @ state.hub_axes[i].T


def _extent(state: RunState) -> float:
    points = np.concatenate([b.centre_line.reshape(-1, 3) for b in state.beams])
    return float(np.max(np.ptp(points, axis=0))) or 1.0


def frame_indices(state: RunState, stride: int = 1) -> np.ndarray:
    """The output times drawn: every ``stride``-th from the first."""
    return np.arange(0, state.times.size, int(stride))


def build(state: RunState, color: str = "strain", stride: int = 1, size=(7.0, 5.6), dpi: int = 90):
    """(figure, update(frame index), frame indices): the figure drawn at the first frame and
    the function that draws it at output time i."""
    coloring = COLORINGS[color]
    frames = frame_indices(state, stride)
    fig = plt.figure(figsize=size, dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    # fixed limits over the whole run: every ribbon edge and the hub, the same span on each axis
    corners = [ribbon_quads(state, k, i).reshape(-1, 3) for k in range(len(state.beams)) for i in frames]
    corners.append(np.concatenate([hub_polygon(state, i) for i in frames]))
    view = _view(np.concatenate(corners))
    low, high = view.min(axis=0), view.max(axis=0)
    centre, half = 0.5 * (low + high), 0.5 * max(float(np.max(high - low)), 1e-9) * 1.05
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("\u2212z (m)")
    ax.set_zlabel("y (m), hub axis")
    values = None
    if coloring.values is not None:
        values = [np.asarray(coloring.values(state, k))[frames] for k in range(len(state.beams))]
        lo = min(float(v.min()) for v in values)
        hi = max(float(v.max()) for v in values)
        if color == "strain":  # strain: symmetric about zero, tension red
            lo, hi = -max(abs(lo), abs(hi), 1e-300), max(abs(lo), abs(hi), 1e-300)
        norm = matplotlib.colors.Normalize(lo, hi if hi > lo else lo + 1e-300)
        cmap = plt.get_cmap("coolwarm" if color == "strain" else "viridis")
        mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
        fig.colorbar(mappable, ax=ax, shrink=0.6, pad=0.1, label=coloring.label)
    hub = Poly3DCollection([_view(hub_polygon(state, 0))], facecolor="0.75", edgecolor="0.35", alpha=0.8)
    ax.add_collection3d(hub)
    (spoke,) = ax.plot([], [], [], color="k", lw=2)
    ribbons = []
    for k in range(len(state.beams)):
        r = Poly3DCollection(_view(ribbon_quads(state, k, 0)), edgecolor="0.2", linewidth=0.3,
                             facecolor=f"C{k % 10}")
        ax.add_collection3d(r)
        ribbons.append(r)
    (hinges,) = ax.plot([], [], [], linestyle="none", marker="o", color="k", markersize=5)
    label = ax.text2D(0.02, 0.95, "", transform=ax.transAxes)
    ax.set_title(state.name)

    def update(i):
        disc = hub_polygon(state, i)
        hub.set_verts([_view(disc)])
        tip = _view(np.array([[0.0, 0.0, 0.0], disc[0]]))
        spoke.set_data_3d(tip[:, 0], tip[:, 1], tip[:, 2])
        for k, r in enumerate(ribbons):
            r.set_verts(_view(ribbon_quads(state, k, i)))
            if values is not None:
                v = values[k][np.searchsorted(frames, i)]
                r.set_facecolor(cmap(norm(0.5 * (v[:-1] + v[1:]))))
        if state.joints:
            at = _view(np.array([state.beams[k].centre_line[i, 0] for k in state.joints]))
            hinges.set_data_3d(at[:, 0], at[:, 1], at[:, 2])
        label.set_text(f"t = {state.times[i]:.3f} s")
        return [hub, spoke, hinges, label, *ribbons]

    update(frames[0])
    return fig, update, frames


def animate(state: RunState, path, color: str = "strain", stride: int = 1, fps: float = 20.0,
            ffmpeg: str | None = None) -> int:
    """Write the animation to ``path``: GIF (Pillow) or, with ``ffmpeg`` (the binary's path),
    MP4 (H.264). Returns the number of frames."""
    fig, update, frames = build(state, color, stride)
    try:
        # the writer's own loop: each frame is drawn once (FuncAnimation.save draws it twice on Agg)
        with matplotlib.rc_context({"animation.ffmpeg_path": ffmpeg} if ffmpeg is not None else {}):
            writer = (animation.PillowWriter(fps=fps) if ffmpeg is None else
                      animation.FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt", "yuv420p"]))
            # not writer.saving(): on an interruption its finish() would write the frames so far
            # (Pillow fails on none with an IndexError that hides the interruption)
            writer.setup(fig, str(path), fig.dpi)
            try:
                for i in frames:
                    update(i)
                    writer.grab_frame()
            except BaseException:
                process = getattr(writer, "_proc", None)  # ffmpeg, when it runs
                if process is not None:
                    process.kill()
                    process.wait()
                raise
            writer.finish()
    finally:
        plt.close(fig)
    return int(frames.size)


def save_frame(state: RunState, path, i: int, color: str = "strain") -> None:
    """One output time as a still figure (PNG, PDF, ...)."""
    fig, update, _ = build(state, color)
    try:
        update(i)
        fig.savefig(path)
    finally:
        plt.close(fig)


def find_ffmpeg() -> str | None:
    """The ffmpeg binary of the package imageio-ffmpeg (the extra ``video``), else one on the PATH, else None."""
    import shutil

    try:
        import imageio_ffmpeg

        return imageio_ffmpeg.get_ffmpeg_exe()
    except (ImportError, RuntimeError):
        return shutil.which("ffmpeg")
