"""Natural frequencies of the hub-beam system linearised about an equilibrium.

The linearised constrained system M dx'' + K dx = 0 with A dx = 0 is reduced to the
null space N of the constraint Jacobian A (scipy.linalg.null_space), and the
generalized eigenproblem (N^T K N) v = omega^2 (N^T M N) v is solved with scipy's
symmetric solver (eigh) when the reduced stiffness is symmetric, with eig otherwise
(a fixed-direction tip moment makes the load stiffness non-symmetric).
Rigid-body modes are left out: with a free hub exactly one (the rotation of hub and
beam about j0). For a straight beam its frequency is zero to round-off; about a bent
equilibrium the discrete model gives it a small non-zero frequency, because the twist
relative to a fixed chart that a rigid rotation needs is not a cubic along a bent element
(the paper's Cardan-angle element shares this); it vanishes under mesh refinement
(tests/solvers/test_modal.py) and is reported as ``rigid_frequencies_hz``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eig, eigh, null_space

from hubbeam.solvers.static import StaticSolution
from hubbeam.system.model import HubSystem


@dataclass
class Modes:
    """Natural frequencies (Hz, ascending), mode shapes (columns over x) and rigid-mode count."""

    frequencies_hz: np.ndarray
    shapes: np.ndarray
    rigid_frequencies_hz: np.ndarray

    @property
    def rigid_modes(self) -> int:
        return int(self.rigid_frequencies_hz.shape[0])


def modal_analysis(
    system: HubSystem, equilibrium: StaticSolution, count: int = 6, free_hub: bool | None = None,
    rigid_tol_hz: float = 1e-3,
) -> Modes:
    """Lowest ``count`` elastic natural frequencies about ``equilibrium``.

    ``free_hub`` (default: the system's motion is "free") releases the hub angle so the
    rigid rotation of hub and beam is a zero mode, which is left out; modes below
    ``rigid_tol_hz`` are left out as rigid in any case.
    """
    if free_hub is None:
        free_hub = system.motion == "free"
    K, M, A = system.linearised(
        equilibrium.x, equilibrium.multipliers, equilibrium.chart, equilibrium.load_factor, held=not free_hub
    )
    N = null_space(A)
    Kr = N.T @ K @ N
    Mr = N.T @ M @ N
    asym = np.max(np.abs(Kr - Kr.T)) / max(np.max(np.abs(Kr)), 1e-300)
    if asym < 1e-9:
        w2, V = eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
    else:
        w2, V = eig(Kr, Mr)
        order = np.argsort(w2.real)
        w2, V = w2.real[order], V.real[:, order]
    f = np.sqrt(np.abs(w2)) * np.sign(w2) / (2.0 * np.pi)
    rigid = np.abs(f) < rigid_tol_hz
    if free_hub:
        rigid[np.argmin(np.abs(f))] = True
    elastic = np.flatnonzero(~rigid)[:count]
    return Modes(f[elastic], N @ V[:, elastic], f[rigid])
