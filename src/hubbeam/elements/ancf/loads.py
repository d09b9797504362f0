"""Loads along the ANCF beam: a distributed load per unit length (gravity, paper Eq. 32) and the
air drag on the centre line's velocity (Eqs. 37-39) with its damping matrix. Coordinates:
:mod:`hubbeam.elements.ancf.coordinates`.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.elements.ancf.coordinates import ELEMENT_DOFS, NODE_DOFS, VEC_OFFSETS


def distributed_load(n_el, length, S, w, density, load) -> np.ndarray:
    """Generalized force (n_el + 1 nodes) of the load per unit length density[el, g] * ``load``
    (``load`` global, e.g. rho A (kg/m) times g (m/s^2): N/m): int S1^T p dx (Eq. 32). Set-up
    work in numpy, as :func:`translational_mass_blocks`."""
    out = np.zeros(NODE_DOFS * (n_el + 1))
    rows = np.add.outer(np.asarray(VEC_OFFSETS), np.arange(3))  # (4, 3): r and r' of both nodes
    for el in range(n_el):
        rows_el = NODE_DOFS * el + rows
        for g in range(w.shape[0]):
            out[rows_el] += (w[g] * length * S[g])[:, None] * (density[el, g] * load)[None, :]
    return out


@njit(cache=True, error_model="numpy")


def drag_kernel(qdot, length, S, w, frontal_width, c1, c2, scale, force, blocks):
    """Damping of Eq. 37-39: f_d = -(c1 + c2 |v|) v per unit frontal area on the centre-line
    velocity v, times the frontal width b per unit length (``frontal_width[el, g]``, m).

    ``force`` (n_dof) is overwritten with Q_d; ``scale`` times -dQ_d/dqdot (the damping
    matrix) is added to ``blocks`` (n_el, 16, 16) unless ``blocks`` is empty.
    Returns the dissipated power -Q_d . qdot (W).
    """
    n_el = (qdot.shape[0] - NODE_DOFS) // NODE_DOFS
    force[:] = 0.0
    if c1 == 0.0 and c2 == 0.0:
        return 0.0
    want_matrix = blocks.shape[0] == n_el
    power = 0.0
    v = np.empty(3)
    for el in range(n_el):
        ve = qdot[NODE_DOFS * el : NODE_DOFS * el + ELEMENT_DOFS]
        for g in range(w.shape[0]):
            v[:] = 0.0
            for a in range(4):
                o = VEC_OFFSETS[a]
                for k in range(3):
                    v[k] += S[g, a] * ve[o + k]
            speed = np.sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)
            jw = w[g] * length * frontal_width[el, g]
            coef = c1 + c2 * speed
            power += jw * coef * speed * speed
            for a in range(4):
                oa = VEC_OFFSETS[a]
                for k in range(3):
                    force[NODE_DOFS * el + oa + k] -= jw * S[g, a] * coef * v[k]
                if not want_matrix:
                    continue
                for b in range(4):
                    ob = VEC_OFFSETS[b]
                    for k in range(3):
                        for m in range(3):
                            Ckm = coef if k == m else 0.0
                            if speed > 0.0:
                                Ckm += c2 * v[k] * v[m] / speed
                            blocks[el, oa + k, ob + m] += scale * jw * S[g, a] * S[g, b] * Ckm
    return power
