"""The hub and its beams in 3D over a run (matplotlib animation, Agg). Numerics never import this module.

Input: a run's recorded state (:class:`hubbeam.io.state.RunState`). Each beam is drawn as a
ribbon, its centre line -+ (b/2) m at every stored station (b the station's width, m the
section's unit vector along it), so twist and bending of the sections show; the rigid bodies
(:func:`hubbeam.io.bodies.rigid_bodies`) by their glyphs: the hub a disc of the hub radius
(the largest root radius) normal to j0, with a spoke along i_h(theta) that turns with it,
each tip body the box of its mass and inertia; a hinge (a beam's root on a revolute joint) a
black dot at the beam's root. Axes: global x, -z and y (so the hub axis j0
points up and the view stays right-handed), the same limits in every frame (the whole run's
extent) and equal scales. One frame per stored output time, or every ``stride``-th.

``scale`` magnifies the deflections: each centre-line point is drawn at the undeformed beam
turned with the hub plus ``scale`` times its deflection from there
(:meth:`hubbeam.io.state.BeamTrack.displacement`); the sections' orientation is the computed
one. ``view`` places the camera: a name of :data:`VIEWS` or (elevation, azimuth) in degrees
(matplotlib's, in the drawn axes x, -z, y: elevation 90 looks down the hub axis).
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import animation  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from hubbeam.io.bodies import RigidBody, rigid_bodies  # noqa: E402
from hubbeam.io.state import RunState  # noqa: E402

#: named camera views: (elevation, azimuth) in degrees
VIEWS = {
    "iso": (25.0, -60.0),  # the default: from above the hub plane, obliquely
    "top": (90.0, -90.0),  # down the hub axis j0 onto the hub plane, x to the right
    "front": (0.0, -90.0),  # edge-on to the hub plane, along global z: x to the right, j0 up
    "side": (0.0, 0.0),  # edge-on to the hub plane, along global x: -z to the right, j0 up
}


@dataclass(frozen=True)
class Coloring:
    """A quantity to colour the ribbons by: ``label`` (with units) and ``values(state, k)``
    giving beam k's (nt, n) values at its stations, or None for a plain colour."""

    label: str
    values: object


#: --color choices: the upper surface's axial strain, the deflection's magnitude, or one colour
COLORINGS = {
    "strain": Coloring("upper-surface axial strain (\u00b5\u03b5)", lambda state, k: 1e6 * state.beams[k].surface_strain),
    "deflection": Coloring("deflection (m)",
                           lambda state, k: np.linalg.norm(state.displacement(k), axis=2)),
    "none": Coloring("", None),
}


def _view(points: np.ndarray) -> np.ndarray:
    """Global (x, y, z) -> plot (x, -z, y): j0 up, right-handed."""
    p = np.asarray(points)
    return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)


def ribbon_quads(state: RunState, k: int, i: int, scale: float = 1.0) -> np.ndarray:
    """Beam k's ribbon at output time i: (n - 1, 4, 3) quadrilaterals, global coordinates (m);
    ``scale`` magnifies the deflection (see the module doc)."""
    beam = state.beams[k]
    half = 0.5 * beam.width[:, None] * beam.m[i]
    centre = beam.centre_line[i]
    if scale != 1.0:
        centre = centre + (scale - 1.0) * state.displacement(k, slice(i, i + 1))[0]
    left, right = centre - half, centre + half
    return np.stack([left[:-1], right[:-1], right[1:], left[1:]], axis=1)


def body_faces(body: RigidBody, i: int) -> list[np.ndarray]:
    """A rigid body's glyph at output time i: its faces as (k, 3) polygons, global (m)."""
    vertices, faces = body.surface(i)
    return [vertices[f] for f in faces]




def _extent(state: RunState) -> float:
    points = np.concatenate([b.centre_line.reshape(-1, 3) for b in state.beams])
    return float(np.max(np.ptp(points, axis=0))) or 1.0


def frame_indices(state: RunState, stride: int = 1) -> np.ndarray:
    """The output times drawn: every ``stride``-th from the first."""
    return np.arange(0, state.times.size, int(stride))


def camera(view) -> tuple[float, float]:
    """(elevation, azimuth) in degrees of a view: a name of :data:`VIEWS` or a pair of numbers;
    ValueError for anything else."""
    if isinstance(view, str):
        if view in VIEWS:
            return VIEWS[view]
        try:
            elevation, azimuth = (float(v) for v in view.split(","))
        except ValueError:
            raise ValueError(f"unknown view {view!r} (use {', '.join(VIEWS)} or ELEVATION,AZIMUTH in degrees)") from None
    else:
        elevation, azimuth = (float(v) for v in view)
    if not (np.isfinite(elevation) and np.isfinite(azimuth) and -90.0 <= elevation <= 90.0):
        raise ValueError(f"view ({elevation:g}, {azimuth:g}): the elevation must be between -90 and 90 degrees")
    return elevation, azimuth


def build(state: RunState, color: str = "strain", stride: int = 1, size=(7.0, 5.6), dpi: int = 90,
          scale: float = 1.0, view="iso"):
    """(figure, update(frame index), frame indices): the figure drawn at the first frame and
    the function that draws it at output time i; ``scale`` and ``view`` as in the module doc."""
    coloring = COLORINGS[color]
    frames = frame_indices(state, stride)
    bodies = rigid_bodies(state, scale)
    fig = plt.figure(figsize=size, dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    # fixed limits over the whole run: every ribbon edge and every body, the same span on each axis
    corners = [ribbon_quads(state, k, i, scale).reshape(-1, 3) for k in range(len(state.beams)) for i in frames]
    corners += [body.surface(i)[0] for body in bodies for i in frames]
    view_points = _view(np.concatenate(corners))
    low, high = view_points.min(axis=0), view_points.max(axis=0)
    centre, half = 0.5 * (low + high), 0.5 * max(float(np.max(high - low)), 1e-9) * 1.05
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    elevation, azimuth = camera(view)
    ax.view_init(elevation, azimuth)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("\u2212z (m)")
    if abs(elevation) < 75.0:  # looking down the hub axis its labels would lie on top of each other
        ax.set_zlabel("y (m), hub axis")
    else:
        ax.set_zticks([])
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
    solids = []
    for body in bodies:
        solid = Poly3DCollection([_view(f) for f in body_faces(body, 0)], facecolor="0.75" if body.name == "hub"
                                 else "0.55", edgecolor="0.3", linewidth=0.3, alpha=0.85)
        ax.add_collection3d(solid)
        solids.append((body, solid))
    (spoke,) = ax.plot([], [], [], color="k", lw=2)
    ribbons = []
    for k in range(len(state.beams)):
        r = Poly3DCollection(_view(ribbon_quads(state, k, 0, scale)), edgecolor="0.2", linewidth=0.3,
                             facecolor=f"C{k % 10}")
        ax.add_collection3d(r)
        ribbons.append(r)
    (hinges,) = ax.plot([], [], [], linestyle="none", marker="o", color="k", markersize=5)
    label = ax.text2D(0.02, 0.95, "", transform=ax.transAxes)
    ax.set_title(state.name + (f" (deflections \u00d7 {scale:g})" if scale != 1.0 else ""))
    hub = bodies[0]

    def update(i):
        for body, solid in solids:
            solid.set_verts([_view(f) for f in body_faces(body, i)])
        spoke_end = _view(np.array([hub.position[i], hub.position[i] + hub.half_size[0] * hub.rotation[i][:, 0]]))
        spoke.set_data_3d(spoke_end[:, 0], spoke_end[:, 1], spoke_end[:, 2])
        for k, r in enumerate(ribbons):
            r.set_verts(_view(ribbon_quads(state, k, i, scale)))
            if values is not None:
                v = values[k][np.searchsorted(frames, i)]
                r.set_facecolor(cmap(norm(0.5 * (v[:-1] + v[1:]))))
        if state.joints:  # each hinge at its beam's drawn root: the middle of the ribbon's first edge
            at = _view(np.array([ribbon_quads(state, k, i, scale)[0, :2].mean(axis=0) for k in state.joints]))
            hinges.set_data_3d(at[:, 0], at[:, 1], at[:, 2])
        label.set_text(f"t = {state.times[i]:.3f} s")
        return [spoke, hinges, label, *ribbons, *(solid for _, solid in solids)]

    update(frames[0])
    return fig, update, frames


def animate(state: RunState, path, color: str = "strain", stride: int = 1, fps: float = 20.0,
            ffmpeg: str | None = None, scale: float = 1.0, view="iso") -> int:
    """Write the animation to ``path``: GIF (Pillow) or, with ``ffmpeg`` (the binary's path),
    MP4 (H.264); ``scale`` and ``view`` as in the module doc. Returns the number of frames."""
    fig, update, frames = build(state, color, stride, scale=scale, view=view)
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


def save_frame(state: RunState, path, i: int, color: str = "strain", scale: float = 1.0, view="iso",
               size=(7.0, 5.6), dpi: int = 90) -> None:
    """One output time as a still figure (PNG, PDF, ...)."""
    fig, update, _ = build(state, color, size=size, dpi=dpi, scale=scale, view=view)
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
