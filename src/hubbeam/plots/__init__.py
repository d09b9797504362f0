"""Figures (matplotlib, Agg backend), in one style (:mod:`hubbeam.plots.style`). Numerics never
import this package.

- :mod:`~hubbeam.plots.style`: sizes, fonts, titles (scenario name and ``--set`` overrides),
  physical names and units;
- :mod:`~hubbeam.plots.timeseries`: a run's time series (``run --plot``), runs compared;
- :mod:`~hubbeam.plots.shapes`: a deformed state (``static --plot``), mode shapes (``modes --plot``);
- :mod:`~hubbeam.plots.studies`: sweeps, identification, FFR applicability, curves against a parameter;
- :mod:`~hubbeam.plots.campbell`: the Campbell diagram.
"""

from hubbeam.plots.campbell import plot_campbell
from hubbeam.plots.shapes import plot_deformed, plot_mode_shapes
from hubbeam.plots.studies import plot_applicability, plot_fit, plot_sweep, plot_xy
from hubbeam.plots.style import paper_style, quantity, run_title
from hubbeam.plots.timeseries import MAX_PANELS, Panel, plot_comparison, plot_timeseries, timeseries_panels

__all__ = ["MAX_PANELS", "Panel", "paper_style", "plot_applicability", "plot_campbell", "plot_comparison",
           "plot_deformed", "plot_fit", "plot_mode_shapes", "plot_sweep", "plot_timeseries", "plot_xy", "quantity",
           "run_title", "timeseries_panels"]
