"""One contraction of an FFR beam's inertia invariants with its elastic coordinates
(:func:`hubbeam.elements.ffr.kernels._moments`: St, Q2 = p II, Q2d = p' II, R2) on experiment
1's beam, nodal (6 elements, nf 36) and on 4 modes: process time per call (us, best of 5 of
200 000 calls; numba's cache warm).

    python benchmarks/moments_cost.py
"""
import time

import numpy as np
from numba import njit

from hubbeam import api
from hubbeam.elements.ffr import constants as fc
from hubbeam.elements.ffr import kernels as fk
from hubbeam.io.scenario import load_example
from hubbeam.system.ffr_part import FfrPart


@njit
def loop(n, inv, p, pd, nf, St, Q2, Q2d, R2):
    for _ in range(n):
        fk._moments(inv[1], inv[2], inv[3], inv[4], inv[5], p, pd, True, nf, St, Q2, Q2d, R2)
    return R2[0]


for name, overrides in (("exp1 nodal", ['beam.formulation="ffr"']), ("exp1 4 modes", ['beam.formulation="ffr"', 'beam.modes=4'])):
    system = api.build_system(load_example("exp1", overrides))
    part = next(b for b in system.beams if isinstance(b, FfrPart))
    arrays = fc.pack(part)
    nf = arrays.Mff.shape[0]
    rng = np.random.default_rng(1)
    p, pd = rng.standard_normal(nf), rng.standard_normal(nf)
    St, Q2, Q2d, R2 = np.empty(3), np.empty((3, 3, nf)), np.empty((3, 3, nf)), np.empty(9)
    loop(1, arrays.inv, p, pd, nf, St, Q2, Q2d, R2)
    best = 1e9
    for _ in range(5):
        t = time.process_time()
        loop(200_000, arrays.inv, p, pd, nf, St, Q2, Q2d, R2)
        best = min(best, (time.process_time() - t) / 200_000 * 1e6)
    print(f"{name}: nf {nf}, II entries not zero {arrays.II_value.size} of {9 * nf * nf}: {best:.3f} us per call")
