"""A run's recorded state read back from its NetCDF file (``hubbeam run -o OUT.nc --state``).

:func:`read_state` gives a :class:`RunState`: the output times, the hub angle and, for every
beam, the variables :func:`hubbeam.io.results.state_table` wrote. What draws a run
(:mod:`hubbeam.animate`) or exports it (:mod:`hubbeam.io.vtk`) reads it from here.
"""

from __future__ import annotations

import json
import os
import stat
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hubbeam.errors import ScenarioError

#: a file without a recorded state: the one line that says how to make one
NO_STATE = "has no stored state (run it with --state: hubbeam run FILE.toml -o OUT.nc --state)"


@dataclass(frozen=True)
class BeamTrack:
    """One beam over a run, at its n stations (SI units, global components)."""

    name: str
    formulation: str
    stations: np.ndarray  # (n,) m from the root along the undeformed beam
    width: np.ndarray  # (n,) m
    thickness: np.ndarray  # (n,) m
    reference: np.ndarray  # (n, 3) m: undeformed centre line in the hub's frame at theta = 0
    centre_line: np.ndarray  # (nt, n, 3) m
    m: np.ndarray  # (nt, n, 3) unit vectors along the width
    n: np.ndarray  # (nt, n, 3) unit vectors along the thickness
    surface_strain: np.ndarray  # (nt, n) axial strain on the upper surface
    #: the tip body ({"mass", "inertia", "offset"}: kg, kg m^2 about the tip section axes, m in
    #: them) or None (also for a file written before tip bodies were recorded)
    tip_body: dict | None = None

    def displacement(self, hub_origin: np.ndarray, hub_axes: np.ndarray, times=slice(None)) -> np.ndarray:
        """(nt, n, 3) m at the output ``times`` (a slice or index array; default all) of the hub
        frame's series (origin (nt, 3) m and axes (nt, 3, 3)): the centre line's displacement from
        the undeformed beam carried by the hub's frame (the base and the hub angle), the beam's
        deflection."""
        carried = np.asarray(hub_origin)[times][:, None, :] + np.einsum(
            "tij,nj->tni", np.asarray(hub_axes)[times], self.reference)
        return self.centre_line[times] - carried


@dataclass(frozen=True)
class RunState:
    """A run's recorded state: ``name`` (the scenario's), ``times`` (nt, s), ``hub_angle`` (nt,
    rad), ``hub_radius`` (m), every beam's :class:`BeamTrack`, and the hub's and the base's
    frames over time: ``hub_origin``, ``base_origin`` (nt, 3) m and ``hub_axes``, ``base_axes``
    (nt, 3, 3) (columns, global; the hub's at theta)."""

    name: str
    times: np.ndarray
    hub_angle: np.ndarray
    hub_radius: float
    beams: tuple[BeamTrack, ...]
    #: for the state of a run that stopped early: how far it got and why (from the file's attributes)
    partial: str | None = None
    hub_origin: np.ndarray = None
    hub_axes: np.ndarray = None
    base_origin: np.ndarray = None
    base_axes: np.ndarray = None
    #: the indices of the beams whose root is a hinge (a revolute joint): their first station
    joints: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        nt = np.asarray(self.times).size
        if self.hub_axes is None:  # a file of a hub on a fixed upright axis: A_h(theta) at the origin
            object.__setattr__(self, "hub_axes", hub_rotation(self.hub_angle))
        for name in ("hub_origin", "base_origin"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros((nt, 3)))
        if self.base_axes is None:
            object.__setattr__(self, "base_axes", np.tile(np.eye(3), (nt, 1, 1)))

    def displacement(self, k: int, times=slice(None)) -> np.ndarray:
        """Beam k's deflection (nt, n, 3) m at the output ``times``: :meth:`BeamTrack.displacement`
        from the undeformed beam the hub's frame carries."""
        return self.beams[k].displacement(self.hub_origin, self.hub_axes, times)


def hub_rotation(theta) -> np.ndarray:
    """A_h(theta) (nt x 3 x 3) of Eq. 74 (:func:`hubbeam.system.mount.hub_rotation`) for every hub angle (rad)."""
    from hubbeam.system.mount import hub_rotation as one

    return np.array([one(float(t)) for t in np.atleast_1d(np.asarray(theta, dtype=float))]).reshape(-1, 3, 3)


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)


def _tip_body(value) -> dict | None:
    """A recorded tip body as a dict of finite numbers (mass, 3 inertias, 3 offsets), or
    None; ValueError for anything else."""
    if value is None:
        return None
    body = {"mass": float(value["mass"]), "inertia": [float(x) for x in value["inertia"]],
            "offset": [float(x) for x in value["offset"]]}
    if len(body["inertia"]) != 3 or len(body["offset"]) != 3 or not np.all(np.isfinite(
            [body["mass"], *body["inertia"], *body["offset"]])):
        raise ValueError(f"a tip body is not three inertias and three offsets of finite numbers ({value!r:.80})")
    return body


def read_state(path, option: str = "input") -> RunState:
    """The recorded state of a run's NetCDF file; ScenarioError (one line naming the file) when
    it is not a readable NetCDF file or has no stored state."""
    import h5netcdf

    p = Path(os.fspath(path))
    try:
        st = p.stat()
    except OSError as exc:
        raise ScenarioError(f"{option} {p}: {'no such file' if isinstance(exc, FileNotFoundError) else exc.strerror}") \
            from None
    if not stat.S_ISREG(st.st_mode):
        raise ScenarioError(f"{option} {p}: not a regular file (a run's NetCDF result)")
    try:
        f = h5netcdf.File(p, "r")
    except (OSError, ValueError, KeyError) as exc:  # h5py: "file signature not found" and the like
        raise ScenarioError(f"{option} {p}: not a NetCDF-4 file ({exc.__class__.__name__}); give a run's -o result") \
            from None
    with f:
        if "state_beams" not in f.attrs:
            raise ScenarioError(f"{option} {p}: {NO_STATE}")
        try:
            names = json.loads(_text(f.attrs["state_beams"]))
            formulations = json.loads(_text(f.attrs["state_formulations"]))
            v = f.variables
            tips = json.loads(_text(f.attrs["state_tip_bodies"])) if "state_tip_bodies" in f.attrs else []
            tips = [_tip_body(t) for t in tips] if len(tips) == len(names) else [None] * len(names)
            beams = tuple(BeamTrack(
                name, form, v[f"state_{name}_station"][...], v[f"state_{name}_width"][...],
                v[f"state_{name}_thickness"][...], v[f"state_{name}_reference"][...],
                v[f"state_{name}_centre_line"][...], v[f"state_{name}_m"][...], v[f"state_{name}_n"][...],
                v[f"state_{name}_surface_strain"][...], tip) for name, form, tip in zip(names, formulations, tips))
            partial = None
            if int(f.attrs.get("partial", 0)):
                reached, t_end = f.attrs.get("time_reached"), f.attrs.get("t_end")
                partial = (f"the run stopped at t = {float(reached):g} s" + (f" of {float(t_end):g} s" if t_end is not None
                                                                             else "") +
                           f" ({_text(f.attrs.get('partial_reason', 'partial'))})")
            hinged = json.loads(_text(f.attrs["state_joints"])) if "state_joints" in f.attrs else []
            frames = {name: v[f"state_{name}"][...] for name in ("hub_origin", "hub_axes", "base_origin", "base_axes")
                      if f"state_{name}" in v}
            state = RunState(_text(f.attrs.get("name", p.stem)), v["time"][...], v["state_hub_angle"][...],
                             float(f.attrs["state_hub_radius"]), beams, partial, **frames,
                             joints=tuple(names.index(name) for name in hinged))
        except (KeyError, ValueError, TypeError) as exc:
            raise ScenarioError(f"{option} {p}: the stored state is incomplete ({exc.__class__.__name__}: {exc})") \
                from None
    check_state(state, f"{option} {p}")
    return state


def check_state(state: RunState, where: str) -> None:
    """ScenarioError naming ``where`` (the option and the file) and the variable when a stored
    state cannot be drawn as it is: no output time or no beam, arrays whose lengths disagree
    (with the times, with a beam's stations; the hub's and the base's frames too), output times
    that do not increase strictly, a hub radius or a value that is not a finite number. Everything that draws or exports a
    state relies on these, so they are checked before any output is written."""
    nt = state.times.size
    if nt == 0:
        raise ScenarioError(f"{where}: the stored state has no output time")
    if not state.beams:
        raise ScenarioError(f"{where}: the stored state holds no beam (state_beams is empty)")
    times = np.asarray(state.times, dtype=float)
    if times.ndim != 1:
        raise ScenarioError(f"{where}: the stored state is damaged: time has shape {times.shape}, not one axis")
    steps = np.diff(times)
    bad = np.flatnonzero(~(steps > 0))
    if bad.size and np.all(np.isfinite(times)):
        i = int(bad[0]) + 1
        raise ScenarioError(f"{where}: the stored state is damaged: time {'repeats' if steps[bad[0]] == 0 else 'goes back'}"
                            f" at output {i} ({times[i]:g} s after {times[i - 1]:g} s); output times increase strictly")
    if not (np.isfinite(state.hub_radius) and state.hub_radius >= 0):
        raise ScenarioError(f"{where}: the stored state is damaged: state_hub_radius is {state.hub_radius!r}, not a "
                            "finite radius >= 0 (m)")
    frames = [("state_hub_origin", state.hub_origin, (nt, 3)), ("state_hub_axes", state.hub_axes, (nt, 3, 3)),
              ("state_base_origin", state.base_origin, (nt, 3)), ("state_base_axes", state.base_axes, (nt, 3, 3))]
    shapes = [("state_hub_angle", state.hub_angle, (nt,))] + frames
    for b in state.beams:
        n = np.shape(b.stations)[0] if np.ndim(b.stations) == 1 else -1
        if n < 2:
            raise ScenarioError(f"{where}: the stored state is damaged: state_{b.name}_station has shape "
                                f"{np.shape(b.stations)}, expected two stations or more along one axis")
        shapes += [(f"state_{b.name}_width", b.width, (n,)), (f"state_{b.name}_thickness", b.thickness, (n,)),
                   (f"state_{b.name}_reference", b.reference, (n, 3)),
                   (f"state_{b.name}_centre_line", b.centre_line, (nt, n, 3)),
                   (f"state_{b.name}_m", b.m, (nt, n, 3)), (f"state_{b.name}_n", b.n, (nt, n, 3)),
                   (f"state_{b.name}_surface_strain", b.surface_strain, (nt, n))]
    for name, values, expected in shapes:
        if np.shape(values) != expected:
            raise ScenarioError(f"{where}: the stored state is damaged: {name} has shape {np.shape(values)}, expected "
                                f"{expected} (from {nt} output times and the beam's stations)")
    arrays = [("time", state.times), ("state_hub_angle", state.hub_angle)] + [(n, v) for n, v, _ in frames] + [
        (f"state_{b.name}_{part.rstrip('s') if part == 'stations' else part}", getattr(b, part)) for b in state.beams
        for part in ("stations", "width", "thickness", "reference", "centre_line", "m", "n", "surface_strain")]
    for name, values in arrays:
        bad = ~np.isfinite(np.asarray(values, dtype=float))
        if bad.any():
            when = ""
            if bad.ndim and bad.shape[0] == nt and name != "time":
                when = f" at t = {float(times[np.argmax(bad.reshape(bad.shape[0], -1).any(axis=1))]):g} s"
            raise ScenarioError(f"{where}: the stored state is damaged: {name} is not a finite number{when}")
