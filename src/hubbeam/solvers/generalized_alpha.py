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

from dataclasses import dataclass

import numpy as np

from hubbeam.solvers.errors import ConvergenceError
from hubbeam.system.assembly import Factorisation
from hubbeam.system.model import HubSystem


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


@dataclass(frozen=True)
class NewtonOptions:
    """Newton settings of a step.

    ``tolerance``: on the increment of the coordinates, relative to the beam length (an
    increment-based test: the force residual of a stiff axial beam is floored by round-off
    at EA * 1e-16 * |r'|, far above any fixed force tolerance). For modified Newton the
    increment is multiplied by rate / (1 - rate), the estimate of the remaining error
    from the observed contraction rate (Hairer and Wanner, IV.8).
    ``modified``: reuse the factorised iteration matrix across iterations and steps and
    refresh it when the contraction rate exceeds ``refresh_rate`` (or on the next step
    after a step that needed more than ``refresh_iterations``); full Newton otherwise.
    """

    tolerance: float = 1e-9
    max_iterations: int = 25
    modified: bool = False
    refresh_rate: float = 0.25
    refresh_iterations: int = 6


@dataclass(frozen=True)
class IterationMatrix:
    """A factorised iteration matrix and what it was built for (step size, chart)."""

    lu: Factorisation
    h: float
    chart: np.ndarray

    def valid_for(self, h: float, chart: np.ndarray) -> bool:
        return self.h == h and self.chart is chart

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        return self.lu.solve(rhs)


def factorise(matrix, h: float, chart: np.ndarray) -> IterationMatrix:
    """LU of a system matrix (BandMatrix or DenseMatrix) for step size h in ``chart``."""
    try:
        return IterationMatrix(matrix.factorise(), h, chart)
    except np.linalg.LinAlgError as exc:
        raise ConvergenceError(f"singular iteration matrix (a constraint lost rank or a mass vanished): {exc}") from exc


def init(system: HubSystem, x0: np.ndarray, F: np.ndarray, t0: float = 0.0,
         v0: np.ndarray | None = None) -> AlphaState:
    """Consistent accelerations and multipliers at (x0, v0): M xdd + Phi_x^T lam = Q - f,
    Phi_x xdd = -Phi_tt - (d/dt Phi_x) v (the drive's prescribed angular acceleration and the
    velocity terms of the clamp, which are linear in the beam coordinates and so contribute
    only through theta). ``v0`` defaults to rest and must satisfy Phi_x v0 + Phi_t = 0."""
    v0 = np.zeros_like(x0) if v0 is None else np.asarray(v0, dtype=float)
    s = system.mass_scale
    zero = np.zeros_like(x0)
    m = system.n_constraints(system.motion != "free")
    # force rows (unscaled) at xdd = 0, lambda = 0
    rhs = -system.dynamic_residual(x0, v0, zero, np.zeros(m), F, t0, 1.0, s)
    rhs[1 : 1 + m] = -s * _constraint_acceleration_terms(system, x0, v0, F, t0)
    # the matrix [[M, s Phi_x^T], [s Phi_x, 0]] (coef_k = 0 drops stiffness and the Hessian)
    _, matrix = system.dynamic_equations(x0, v0, zero, np.zeros(m), F, t0, 1.0, 0.0, 0.0, s)
    z = factorise(matrix, 0.0, F).solve(rhs)
    xdd = np.concatenate([[z[0]], z[1 + m :]])
    lam = s * z[1 : 1 + m]
    return AlphaState(t0, x0.copy(), v0.copy(), xdd, xdd.copy(), lam, F)


def _constraint_acceleration_terms(system: HubSystem, x, v, F, t):
    """v^T Phi_xx v + Phi_tt: what the constraint acceleration Phi_x xdd must cancel.

    The clamp has no explicit time dependence and the drive equation theta - theta_p(t)
    has Phi_tt = -theta_p''(t) and no mixed term, so this is exact."""
    held = system.motion != "free"
    _, jac, hess = system.constraints(x, F, system.drive_angle(t, held))
    c = v[0 : jac.shape[1]]  # the constraints involve a leading block of x (the clamp coordinates)
    terms = np.array([c @ hess(e) @ c for e in np.eye(jac.shape[0])])
    if system.motion == "prescribed":
        terms[6] -= system.drive(t)[2]
    return terms


def step(system: HubSystem, state: AlphaState, h: float, p: AlphaParameters,
         options: NewtonOptions = NewtonOptions(), matrix: IterationMatrix | None = None
         ) -> tuple[AlphaState, int, IterationMatrix | None]:
    """One step of length h.

    Returns the new state, the Newton iterations it took and the iteration matrix to
    reuse on the next step (modified Newton; None for full Newton).
    """
    am, af, beta, gamma = p.alpha_m, p.alpha_f, p.beta, p.gamma
    t1 = state.t + h
    # predictor: xdd_{n+1} = xdd_n, and a, x, v consistent with it
    xdd = state.xdd.copy()
    a = ((1.0 - af) * xdd + af * state.xdd - am * state.a) / (1.0 - am)
    v = state.v + h * (1.0 - gamma) * state.a + h * gamma * a
    x = state.x + h * state.v + h * h * (0.5 - beta) * state.a + h * h * beta * a
    lam = state.lam.copy()
    bprime = (1.0 - am) / (beta * h * h * (1.0 - af))
    gprime = gamma / (beta * h)
    ck = beta * h * h
    s = system.mass_scale
    m = lam.shape[0]
    xscale = max(system.length_scale, 1.0)
    tol = options.tolerance * xscale
    coefs = (ck * bprime, ck * gprime, ck, s)

    def fresh_matrix():
        res, matrix = system.dynamic_equations(x, v, xdd, lam, state.chart, t1, *coefs)
        return res, factorise(matrix, h, state.chart)

    if not options.modified or matrix is None or not matrix.valid_for(h, state.chart):
        res, matrix = fresh_matrix()
    else:
        res = system.dynamic_residual(x, v, xdd, lam, state.chart, t1, ck, s)
    previous = np.inf
    for it in range(1, options.max_iterations + 1):
        dz = matrix.solve(-res)
        if not np.all(np.isfinite(dz)):
            raise ConvergenceError("non-finite Newton increment")
        dx = np.concatenate([[dz[0]], dz[1 + m :]])
        x += dx
        v += gprime * dx
        xdd += bprime * dx
        lam += s * dz[1 : 1 + m] / ck
        size = np.max(np.abs(dx))
        rate = size / previous  # 0 on the first iteration with a fresh matrix
        if options.modified and np.isfinite(previous):
            error = size * rate / (1.0 - rate) if rate < 1.0 else np.inf
        else:
            error = size
        if error <= tol:
            a_new = ((1.0 - af) * xdd + af * state.xdd - am * state.a) / (1.0 - am)
            keep = matrix if options.modified and it <= options.refresh_iterations else None
            return AlphaState(t1, x, v, xdd, a_new, lam, state.chart), it, keep
        if not options.modified or rate > options.refresh_rate:
            res, matrix = fresh_matrix()
            previous = np.inf
        else:
            res = system.dynamic_residual(x, v, xdd, lam, state.chart, t1, ck, s)
            previous = size
    raise ConvergenceError(f"Newton did not converge in {options.max_iterations} iterations (last |dx| = {size:.2e})")
