"""The argument parser of every command (one line on a usage error)."""

from __future__ import annotations

import argparse

from hubbeam.cli.common import say

class Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse prints a usage of several lines: one line instead
        say(f"hubbeam: error: {message} (usage: {self.prog} --help)")
        raise SystemExit(2)


def build_parser() -> argparse.ArgumentParser:
    from importlib.metadata import PackageNotFoundError, version

    from hubbeam.io.examples import DATA_FILES, EXAMPLES

    try:
        installed = version("hubbeam")
    except PackageNotFoundError:  # run from a source tree that is not installed
        from hubbeam import __version__ as installed
    p = Parser(prog="hubbeam", description="Rotating hub with flexible 3D beams: ANCF with torsion and FFR, "
                                            "several beams, tip bodies, torque laws.")
    p.add_argument("--version", action="version", version=f"hubbeam {installed}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=Parser)

    def scenario_cmd(name, help_):
        sp = sub.add_parser(name, help=help_)
        sp.add_argument("scenario", help="scenario file (TOML)")
        sp.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                        help="override one key, dotted path and TOML value (e.g. beam.elements=8)")
        sp.add_argument("--json", action="store_true", help="print one JSON object on stdout")
        return sp

    run = scenario_cmd("run", "run the scenario's analysis")
    run.add_argument("-o", "--output", help="NetCDF result file")
    run.add_argument("--csv", help="CSV result file")
    run.add_argument("--plot", help="figure (PNG, PDF, SVG, ...)")
    run.add_argument("--state", action="store_true", help="also store the hub angle and every beam's geometry in the "
                                                          "NetCDF file (-o), for animate and vtk")
    run.add_argument("--plot-vars", metavar="A,B,...",
                     help="variables (or sensors) to draw with --plot (default: every one that is not zero throughout)")
    st = scenario_cmd("static", "static equilibrium under gravity and loads (hub held at theta = 0)")
    st.add_argument("--plot", help="figure of the deformed beam")
    mod = scenario_cmd("modes", "natural frequencies about the static equilibrium (steady rotation for a constant drive)")
    mod.add_argument("--shapes", help="NetCDF file of the mode shapes (docs/modes.md)")
    mod.add_argument("--plot", help="figure of the lowest mode shapes along the span")
    lin = scenario_cmd("linearize", "state space (A, B, C, D) about the equilibrium (steady rotation for a "
                                    "constant drive)")
    lin.add_argument("-o", "--output", help="NetCDF file of A, B, C, D")
    lin.add_argument("--inputs", help="comma-separated: hub_torque, joint_torque:BEAM, tip_force:BEAM, load:NAME (a "
                                      "span load's force per length, or load:tip) (default: "
                                      "hub_torque on a free hub, the first beam's tip force on a held one, and every "
                                      "joint motor's torque)")
    lin.add_argument("--open-loop", action="store_true", help="leave the scenario's torque laws (the hub's and the "
                                                             "joint motors') and its [[controllers]] out (the plant)")
    lin.add_argument("--outputs", metavar="A,B,...", help="only these outputs (sensor columns), in this order")
    size = lin.add_mutually_exclusive_group()
    size.add_argument("--reduce", type=int, metavar="N", help="modal truncation to the N lowest modes, the others "
                                                               "residualised (DC gain kept; rigid, unstable modes kept)")
    size.add_argument("--balanced", type=int, metavar="N", help="balanced reduction of the stable part to N states "
                                                                 "(Hankel singular values in the JSON)")
    lin.add_argument("--fmax", type=float, metavar="F", help="drop (residualise) the modes above F Hz")
    camp = scenario_cmd("campbell", "natural frequencies about the steadily rotating state against hub speed")
    camp.add_argument("--omega", required=True, metavar="START:STOP:N", help="hub speeds (rad/s)")
    camp.add_argument("--count", type=int, default=6, help="modes per speed (default 6)")
    camp.add_argument("-o", "--output", help="figure")
    camp.add_argument("--data", help="NetCDF file of the frequencies")
    camp.add_argument("--formulations", default=None,
                      help="comma-separated: ancf, ffr, ffr+ (default: the scenario's own)")
    camp.add_argument("--frame", choices=("rotating", "fixed"), default="rotating",
                      help="the frame of the diagram: rotating (default) or fixed (multi-blade coordinates: "
                           "progressive and regressive whirl; N >= 3 identical, evenly spaced beams)")
    camp.add_argument("--harmonics", metavar="N,N,...",
                      help="the nP lines to draw (default 1 to 2 x the number of beams)")
    zoom = camp.add_mutually_exclusive_group()
    zoom.add_argument("--fmax", type=float, help="draw frequencies from 0 to FMAX Hz only")
    zoom.add_argument("--frange", metavar="LO:HI", help="draw frequencies from LO to HI Hz only")
    sw = scenario_cmd("sweep", "run the scenario over the cartesian product of varied keys, on Dask")
    sw.add_argument("--vary", action="append", required=True, metavar="KEY=START:STOP:N",
                    help="a varied key and its values (numpy.linspace); repeat for more keys")
    sw.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    sw.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: all cores)")
    sw.add_argument("-o", "--output", required=True, help="NetCDF file of the merged results")
    sw.add_argument("--plot", help="figure of the results (up to four variables)")
    idf = scenario_cmd("identify", "fit scenario parameters to a measured time series (least squares)")
    idf.add_argument("measured", help="CSV with a header row: a 'time' column (s) and the signal's column")
    idf.add_argument("--fit", nargs="+", required=True, metavar="KEY", help="scenario keys to fit (e.g. damping.linear)")
    idf.add_argument("--signal", default="strain_P1", help="the sensor (column) to match (default strain_P1)")
    idf.add_argument("-o", "--output", help="figure of fit and data")
    app = sub.add_parser("applicability", help="map FFR's error against ANCF over deflection and hub speed")
    app.add_argument("scenario", nargs="?", default=None, help="scenario file (default: the bundled exp1)")
    app.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    app.add_argument("--thickness", default="0.001:0.004:7", metavar="START:STOP:N", help="plate thickness (m)")
    app.add_argument("--ratio", default="0:0.6:7", metavar="START:STOP:N", help="hub speed / first natural frequency")
    app.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster here)")
    app.add_argument("--workers", type=int, default=None, help="LocalCluster worker processes (default: all cores)")
    app.add_argument("-o", "--output", required=True, help="directory for applicability.png, .nc and .md")
    app.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    rep = sub.add_parser("reproduce", help="rerun the paper's tables and figures (Secs. 5 and 6)")
    rep.add_argument("-o", "--output", required=True, help="directory for report.md, tables.json and figures")
    rep.add_argument("--quick", action="store_true", help="experiment 2 at dt = 5 ms (same physics; < 10 min on 2 cores)")
    rep.add_argument("--jobs", type=int, default=None, help="parallel runs (default: all cores)")
    an = sub.add_parser("animate", help="the hub and beams of a run stored with --state in 3D, as GIF or MP4")
    an.add_argument("result", help="NetCDF file of hubbeam run -o OUT.nc --state")
    an.add_argument("-o", "--output", required=True, help="movie file: .gif, or .mp4 (needs ffmpeg: the extra 'video')")
    an.add_argument("--color", default="strain", help="strain (upper surface, default), deflection or none")
    an.add_argument("--stride", type=int, default=1, help="draw every N-th stored output time (default 1)")
    an.add_argument("--fps", type=float, default=20.0, help="frames per second of the movie (default 20)")
    an.add_argument("--scale", type=float, default=1.0, metavar="K",
                    help="draw the deflections K times larger (from the undeformed beam turned with the hub; default 1)")
    an.add_argument("--view", default="iso", metavar="VIEW",
                    help="camera: iso (default), top (down the hub axis), front, side, or ELEVATION,AZIMUTH in degrees")
    an.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    vt = sub.add_parser("vtk", help="a run stored with --state as a ParaView time series (.pvd and .vtu files)")
    vt.add_argument("result", help="NetCDF file of hubbeam run -o OUT.nc --state")
    vt.add_argument("-o", "--output", required=True, help="directory for NAME.pvd and NAME_NNNNN.vtu")
    vt.add_argument("--force", action="store_true", help="replace a series of the same name already in the directory")
    vt.add_argument("--json", action="store_true", help="print one JSON object on stdout")
    ex = sub.add_parser("example", help="print a bundled scenario (or a bundled data file)")
    ex.add_argument("name", help=f"one of: {', '.join(EXAMPLES)}; or a data file: {', '.join(DATA_FILES)}")
    return p


