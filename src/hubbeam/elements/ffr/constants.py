"""The constants of an FFR part for the compiled kernels (:mod:`hubbeam.elements.ffr.kernels`):
its beam's inertia invariants (the tip body folded in), stiffness, structural damping, tip
loads and the centre-line table of the drag, as contiguous float64 arrays and floats
(:class:`FfrArrays`, built by :func:`pack`; the kernels' argument groups ``inv``, ``tip`` and
``drag`` are its properties).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from hubbeam.elements.ffr.drag import point_spans
from hubbeam.elements.ffr.kernels import kernel_work, sparse_entries


class FfrArrays(NamedTuple):
    """An FFR part's constants as float64 arrays and floats (:func:`pack`)."""

    m: float
    c0: np.ndarray  # (3,)
    Sbar: np.ndarray  # (3, nf)
    I0: np.ndarray  # (3, 3)
    J: np.ndarray  # (3, 3, nf)
    II_start: np.ndarray  # (9 nf + 1,) int64: II (3, 3, nf, nf) by its entries that are not zero (sparse_entries)
    II_column: np.ndarray  # (nnz,) int64
    II_value: np.ndarray  # (nnz,)
    Mff: np.ndarray  # (nf, nf)
    K: np.ndarray  # (nf, nf): Eq. 61, without its axial part when stiffening
    EAl: np.ndarray  # (n_el,) int_e EA dx (N m)
    mean_stretch: np.ndarray  # (n_el, nf)
    mean_slope2: np.ndarray  # (n_el, nf, nf)
    stiffening: float  # 1.0 or 0.0
    C_struct: np.ndarray  # (nf, nf) c K: structural damping (N s)
    damped: float  # 1.0 when c > 0, else 0.0
    tip_force: np.ndarray  # (3,) global
    tip_moment: np.ndarray  # (3,) global
    tip_rows: np.ndarray  # (3, nf): displacement_row(L)
    tip_rotation_rows: np.ndarray  # (3, nf): rotation_row(L)
    length: float
    N_pts: np.ndarray  # (npts, 3, nf): centre-line Gauss table
    N_span: np.ndarray  # (npts, 2) int64: where N_pts[k] is not zero (point_spans)
    x_pts: np.ndarray  # (npts,)
    w_pts: np.ndarray  # (npts,)
    width: np.ndarray  # (npts,) frontal width b of the drag at the centre-line points (m)

    @property
    def inv(self) -> tuple:
        return (self.m, self.c0, self.Sbar, self.I0, self.J, (self.II_start, self.II_column, self.II_value), self.Mff, self.K, self.EAl,
                self.mean_stretch, self.mean_slope2, self.stiffening, self.C_struct, self.damped)

    @property
    def tip(self) -> tuple:
        return (self.tip_force, self.tip_moment, self.tip_rows, self.tip_rotation_rows, self.length)

    def drag(self, damping=(0.0, 0.0)) -> tuple:
        return (self.N_pts, self.N_span, self.x_pts, self.w_pts, self.width, float(damping[0]), float(damping[1]))

    def work(self) -> tuple:
        """Scratch of :func:`ffr_vspace_terms` for this part (:func:`kernel_work`)."""
        return kernel_work(self.Mff.shape[0], self.x_pts.shape[0])


def _f64(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64)


def pack(part) -> FfrArrays:
    """The constants of an :class:`~hubbeam.system.ffr_part.FfrPart` (its FfrBeam, tip body
    folded in the invariants, tip force and moment) for the kernels."""
    beam = part.beam
    inv = beam.invariants
    stiff = bool(beam.geometric_stiffening)
    K = beam.stiffness_matrix - beam._axial_stiffness if stiff else beam.stiffness_matrix
    t = beam.centre_line_table
    II_start, II_column, II_value = sparse_entries(inv["II"])
    return FfrArrays(
        m=float(inv["m"]), c0=_f64(inv["c0"]), Sbar=_f64(inv["Sbar"]), I0=_f64(inv["I0"]), J=_f64(inv["J"]),
        II_start=II_start, II_column=II_column, II_value=II_value, Mff=_f64(inv["Mff"]), K=_f64(K),
        EAl=_f64(beam.axial_integrals),
        mean_stretch=_f64(t["mean_stretch"]), mean_slope2=_f64(t["mean_slope2"]), stiffening=1.0 if stiff else 0.0,
        C_struct=_f64(beam.damping_matrix), damped=1.0 if beam.structural_damping > 0.0 else 0.0,
        tip_force=_f64(part.tip_force), tip_moment=_f64(part.tip_moment),
        tip_rows=_f64(beam.displacement_row(beam.length)), tip_rotation_rows=_f64(beam.rotation_row(beam.length)),
        length=float(beam.length), N_pts=_f64(t["N"]), N_span=point_spans(t["N"]), x_pts=_f64(t["x"]), w_pts=_f64(t["w"]),
        width=_f64(t["b"]),
    )
