"""Generalized-alpha for the index-3 DAE of the hub-beam system (paper refs. [31, 32]).

Chung-Hulbert parameters from the spectral radius at infinity rho:
alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
beta = (gamma + 1/2)^2 / 4. Arnold and Bruels's form for constrained systems: the
equations of motion and the constraints Phi(x, t) = 0 are enforced at t_{n+1}, with the
algorithmic acceleration a:

    (1 - alpha_m) a_{n+1} + alpha_m a_n = (1 - alpha_f) xdd_{n+1} + alpha_f xdd_n
    x_{n+1} = x_n + h v_n + h^2 (1/2 - beta) a_n + h^2 beta a_{n+1}
    v_{n+1} = v_n + h (1 - gamma) a_n + h gamma a_{n+1}

Newton corrects x with dv = gamma' dx, dxdd = beta' dx, beta' = (1 - alpha_m)/(beta h^2
(1 - alpha_f)), gamma' = gamma/(beta h). The force rows are scaled by beta h^2 and the
constraint rows by a mass scale (Bottasso et al.), so the iteration matrix
(1 - alpha_m)/(1 - alpha_f) M + gamma h C + beta h^2 K has entries of one size.
Integrators are plain ``init``/``step`` pairs on an explicit :class:`AlphaState`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg.lapack import dgbtrf, dgbtrs

from hubbeam.solvers.errors import ConvergenceError
from hubbeam.system.beam import ChartSingularityError
from hubbeam.system.model import HubBeamSystem


@dataclass(frozen=True)
class AlphaParameters:
    alpha_m: float
    alpha_f: float
    beta: float
    gamma: float

    @classmethod
    def from_spectral_radius(cls, rho: float) -> "AlphaParameters":
        if not 0.0 <= rho <= 1.0:
            raise ValueError("spectral radius must lie in [0, 1]")
        am = (2.0 * rho - 1.0) / (rho + 1.0)
        af = rho / (rho + 1.0)
        gamma = 0.5 + af - am
        return cls(am, af, 0.25 * (gamma + 0.5) ** 2, gamma)


@dataclass(frozen=True)
class AlphaState:
    """Explicit integrator state: time, coordinates, velocities, accelerations, multipliers, chart."""

    t: float
    x: np.ndarray
    v: np.ndarray
    xdd: np.ndarray
    a: np.ndarray
    lam: np.ndarray
    chart: np.ndarray


def _solve(ab, bw, rhs):
    lu, piv, info = dgbtrf(ab, bw, bw)
    if info != 0:
        raise ConvergenceError("singular iteration matrix")
    sol, info = dgbtrs(lu, bw, bw, rhs, piv)
    return sol


def mass_scale(system: HubBeamSystem) -> float:
    return system.beam.section.mass_per_length * system.beam.element_length


def init(system: HubBeamSystem, x0: np.ndarray, F: np.ndarray, t0: float = 0.0) -> AlphaState:
    """Consistent accelerations and multipliers at a state of rest: M xdd + Phi_x^T lam = Q - f,
    Phi_x xdd = -Phi_tt (the drive's prescribed angular acceleration)."""
    v0 = np.zeros_like(x0)
    s = mass_scale(system)
    zero = np.zeros_like(x0)
    m = system.n_constraints(system.motion != "free")
    res, ab, bw = system.dynamic_equations(x0, v0, zero, np.zeros(m), F, t0, 1.0, 0.0, 0.0, s)
    # the linear problem: rows of res are (-Q + f) and s Phi; replace the latter by -s Phi_tt
    rhs = -res
    rhs[1 : 1 + m] = 0.0
    if system.motion == "prescribed":
        rhs[1 + 6] = s * system.drive(t0)[2]
    # dynamic_equations with coef_k = 0 scales the force rows by 0: redo them unscaled
    res_f, _, _ = system.dynamic_equations(x0, v0, zero, np.zeros(m), F, t0, 1.0, 0.0, 1.0, s)
    rhs[0] = -res_f[0]
    rhs[1 + m :] = -res_f[1 + m :]
    z = _solve(ab, bw, rhs)
    xdd = np.concatenate([[z[0]], z[1 + m :]])
    lam = s * z[1 : 1 + m]
    return AlphaState(t0, x0.copy(), v0, xdd, xdd.copy(), lam, F)


def step(system: HubBeamSystem, state: AlphaState, h: float, p: AlphaParameters, tol: float = 1e-9,
         max_iterations: int = 25) -> tuple[AlphaState, int]:
    """One step of length h; returns the new state and the Newton iterations it took."""
    am, af, beta, gamma = p.alpha_m, p.alpha_f, p.beta, p.gamma
    t1 = state.t + h
    # predictor: xdd_{n+1} = 0, and a, x, v consistent with it (Arnold and Bruels)
    xdd = np.zeros_like(state.xdd)
    a = (af * state.xdd - am * state.a) / (1.0 - am)
    v = state.v + h * (1.0 - gamma) * state.a + h * gamma * a
    x = state.x + h * state.v + h * h * (0.5 - beta) * state.a + h * h * beta * a
    lam = state.lam.copy()
    bprime = (1.0 - am) / (beta * h * h * (1.0 - af))
    gprime = gamma / (beta * h)
    ck = beta * h * h
    s = mass_scale(system)
    m = lam.shape[0]
    xscale = max(system.beam.length, 1.0)
    for it in range(1, max_iterations + 1):
        res, ab, bw = system.dynamic_equations(x, v, xdd, lam, state.chart, t1, ck * bprime, ck * gprime, ck, s)
        dz = _solve(ab, bw, -res)
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("non-finite Newton increment")
        dx = np.concatenate([[dz[0]], dz[1 + m :]])
        x += dx
        v += gprime * dx
        xdd += bprime * dx
        lam += s * dz[1 : 1 + m] / ck
        if np.max(np.abs(dx)) <= tol * xscale:
            a_new = ((1.0 - af) * xdd + af * state.xdd - am * state.a) / (1.0 - am)
            return AlphaState(t1, x, v, xdd, a_new, lam, state.chart), it
    raise ConvergenceError(f"Newton did not converge in {max_iterations} iterations (last |dx| = {np.max(np.abs(dx)):.2e})")
