"""The compiled FFR body terms in v-space (:func:`hubbeam.elements.ffr.kernels.ffr_vspace_terms`)
against their Python reference (:meth:`FfrPart.vspace_forces`) on one beam.

    python benchmarks/ffr_kernel.py

Prints the time of one evaluation of the body's forces and matrices (drag, geometric
stiffening, tip loads, a tip body; 3 elements) by the compiled kernel and by the Python
reference, and their ratio (best of 5 repetitions; a warm numba cache).
"""

from __future__ import annotations

import time

import numpy as np

from hubbeam.elements.ffr import constants as fc
from hubbeam.elements.ffr import kernels as fk
from hubbeam.elements.ffr.body import FfrBeam
from hubbeam.elements.section import Section, saint_venant_torsion_constant
from hubbeam.system.ffr_part import FfrPart
from hubbeam.system.mount import Mount
from hubbeam.system.tip_body import TipBody

GRAVITY = np.array([0.3, -9.81, 0.7])


def part() -> FfrPart:
    """The reference plate (1.45 m x 50 mm x 2.5 mm aluminium) as a stiffened FFR beam of 3
    elements with tip loads and a tip body."""
    b, h, E = 0.05, 0.0025, 70e9
    section = Section(b, h, 2700.0, E, E / 2.66, saint_venant_torsion_constant(b, h))
    beam = FfrBeam(1.45, 3, section, geometric_stiffening=True,
                   tip_body=TipBody(0.2, (1.0e-4, 2.0e-4, 2.5e-4), (0.01, 0.005, -0.003)))
    return FfrPart(beam, Mount(0.2, 0.1, 0.0, 0.05), tip_force=np.array([3.0, -20.0, 12.0]),
                   tip_moment=np.array([0.4, -1.5, 2.0]))


def best(fun, reps: int) -> float:
    times = []
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(reps):
            fun()
        times.append((time.perf_counter() - start) / reps)
    return min(times)


def main() -> None:
    from hubbeam.system.rotations import rotation_vector_matrix

    p = part()
    rng = np.random.default_rng(3)
    nf = p.ndof
    A = rotation_vector_matrix(rng.uniform(-1.2, 1.2, size=3))
    q = 2e-3 * rng.normal(size=nf)
    vb, vdot = 0.3 * rng.normal(size=6 + nf), 10.0 * rng.normal(size=6 + nf)
    damping = (0.4, 1.7)
    arrays = fc.pack(p)
    n = 6 + nf
    fv, Mv, Cv, K_el = np.empty(n), np.empty((n, n)), np.empty((n, n)), np.empty((nf, nf))
    inv, tip, drag, work = arrays.inv, arrays.tip, arrays.drag(damping), arrays.work()

    def kernel():
        fk.ffr_vspace_terms(inv, A, q, vb, vdot, GRAVITY, tip, drag, 1.0, True, fv, Mv, Cv, K_el, work)

    kernel()  # compiled (or loaded from the cache) before timing
    t_kernel = best(kernel, 200)
    t_python = best(lambda: p.vspace_forces(A, q, vb, vdot, GRAVITY, damping, tangent=True), 20)
    print(f"FFR v-space terms (nf = {nf}, drag, stiffening, matrices): kernel {t_kernel * 1e6:.1f} us, "
          f"FfrPart.vspace_forces {t_python * 1e6:.1f} us, ratio {t_python / t_kernel:.0f}x")


if __name__ == "__main__":
    main()
