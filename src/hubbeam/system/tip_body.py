"""A rigid body attached to the tip section of a beam (a tip mass with rotary inertia).

The body has mass m (kg), principal rotary inertia J = (J_tau, J_m, J_n) (kg m^2) about
the tip section's axes (tau, m, n) through its centre of mass, and its centre of mass
sits at the offset c = (c_tau, c_m, c_n) (m) from the tip centroid p, in the tip
section frame. It is rigidly attached: it moves with the tip section's position and
orientation.

**ANCF** (:func:`ancf_tip_body_terms`). The tip node's coordinates are
q8 = [r0 (3), r0' (3), theta_1, theta_1'] (global components). The section frame is
R = F [tau m n](X), X = (U, theta_1), U = F^T r0' (chart components, see
:mod:`hubbeam.elements.ancf.frame`); theta_1' does not move the body. As in
:func:`hubbeam.elements.ancf.inertia.rotary_inertia_kernel`, the section's angular
velocity in its own frame, omega = B(X) Xdot, and d omega / dX are the curvature
measures of :func:`~hubbeam.elements.ancf.strain.strain_jet` evaluated at
Z = (U, Udot, theta_1, theta_1dot) (R^T R' and R^T Rdot are the same function of their
arguments). Then omega_dot = B Xddot + (d omega / dX) Xdot and, Newton-Euler about the
centre of mass, with a_cm = a_p + R (omega_dot x c + omega x (omega x c)):

    f_r = m (a_cm - g)                                        (global)
    h   = J omega_dot + omega x J omega + c x R^T f_r           (section frame)

h is the moment about p; it equals J_p omega_dot + omega x J_p omega + m c x R^T (a_p - g)
with J_p = J + m (|c|^2 I - c c^T) (Huygens-Steiner; c x (w x (w x c)) = w x ((c.c) w - (c.w) c)).
A virtual displacement moves the centre of mass by dr0 + R (dtheta x c) and turns the body
by dtheta = B dX (section frame), so the generalized force on q8 (inertia minus applied,
the sign of the residual rows "M q'' + f_int - Q") has f_r on the r0 rows and B^T h on X,
mapped to global components (r0' rows get F (B^T h)[0:3]). Its parts:

    M_tb = [[m I,  m R [B_k x c]_k], [sym, B^T J_p B]]       (only r0, r0', theta_1 rows)
    -Q_v = [m R ((dw/dX Xdot) x c + w x (w x c)),  B^T (J_p (dw/dX) Xdot + w x J_p w)]
    Q_g  = [m g,  m B^T (c x R^T g)]

and the load stiffness of gravity K_tb = -dQ_g/dq8 (exact; only on the X block):

    K_X[l, k] = -m (sum_i dB_il/dX_k u_i + B_l . (c x (s x B_k))),   s = R^T g, u = c x s

(d(R^T g)/dX_k = s x B_k, dB/dX from strain_jet's Hessian). K_tb is the Hessian of the
potential V = -m g.(r0 + R c), hence symmetric. The derivative of the inertia terms with
respect to q8 (and the velocity terms with respect to v8) is left out of the Newton block, as
in the beam kernels: it is O((omega h)^2) against the mass term and only slows Newton.
With c = 0 and J = 0 everything reduces exactly to a point mass m on r0(L).

**FFR**: :class:`~hubbeam.elements.ffr.body.FfrBeam` takes ``tip_body=`` and adds the body
to its inertia invariants as seven point masses (see :meth:`TipBody.point_masses`).

**The kind "tip bodies"** (:data:`KIND`, :mod:`hubbeam.system.terms`): every tip body on a
beam whose tip is an ANCF node (:meth:`~hubbeam.system.parts.BeamPart.tip_node`) is packed
into :class:`TipBodies`, and its terms, energies (in its beam's row) and nothing else reach
the compiled equations through the registry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from hubbeam.elements.ancf.coordinates import mass_to_global
from hubbeam.elements.ancf.frame import section_frame
from hubbeam.elements.ancf.strain import PHI, PSI, strain_jet, strain_measures
from hubbeam.system import terms
from hubbeam.system.assembly import add_entry

#: Positions of X = (U, theta_1) and of Xdot inside Z = (U, Udot, theta_1, theta_1dot).
_XI = (0, 1, 2, PHI)
_VI = (3, 4, 5, PSI)
#: The rows of q8 that X's four variables (r0' (3), theta_1) occupy.
_QX = (3, 4, 5, 6)


@dataclass(frozen=True)
class TipBody:
    """Rigid tip body: mass (kg), principal rotary inertia (J_tau, J_m, J_n) about the
    section axes through its centre of mass (kg m^2), and the offset (c_tau, c_m, c_n) (m)
    of its centre of mass from the tip centroid, in the tip section frame."""

    mass: float = 0.0
    inertia: tuple = (0.0, 0.0, 0.0)
    offset: tuple = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        mass = float(self.mass)
        inertia = tuple(float(v) for v in np.ravel(np.asarray(self.inertia, dtype=float)))
        offset = tuple(float(v) for v in np.ravel(np.asarray(self.offset, dtype=float)))
        if not math.isfinite(mass) or mass < 0.0:
            raise ValueError(f"tip body mass must be finite and >= 0 (got {mass})")
        if len(inertia) != 3 or len(offset) != 3:
            raise ValueError("tip body inertia and offset need three components each")
        if not all(math.isfinite(v) and v >= 0.0 for v in inertia):
            raise ValueError(f"tip body principal inertias must be finite and >= 0 (got {inertia})")
        if not all(math.isfinite(v) for v in offset):
            raise ValueError(f"tip body offset must be finite (got {offset})")
        tol = 1e-12 * sum(inertia)
        for i in range(3):
            if inertia[i] > inertia[(i + 1) % 3] + inertia[(i + 2) % 3] + tol:
                raise ValueError(f"tip body inertias {inertia} violate the triangle inequality of a rigid body")
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "offset", offset)

    # ------------------------------------------------------------ data
    def params(self) -> np.ndarray:
        """float64[7]: [m, J_tau, J_m, J_n, c_tau, c_m, c_n] (the kernel's ``params``)."""
        return np.array([self.mass, *self.inertia, *self.offset], dtype=np.float64)

    @property
    def second_moments(self) -> np.ndarray:
        """s_k = int d_k^2 dm about the centre of mass in the section axes (kg m^2):
        s_tau = (J_m + J_n - J_tau) / 2 etc. (>= 0 by the triangle inequalities)."""
        J = np.array(self.inertia)
        return np.maximum(0.5 * (J.sum() - 2.0 * J), 0.0)

    def point_masses(self, spread: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Seven weighted points with the body's mass, first and second moments exactly:
        weights (7,) (kg) and offsets d (7, 3) from the tip centroid (m, section axes).

        The centre of mass c carries m - sum_k s_k / a^2 and c +- a e_k carry s_k / (2 a^2)
        each (s = :attr:`second_moments`). Every quantity linear in the mass distribution
        and at most quadratic in the position (an FFR inertia invariant) is then exact for
        any a > 0. The default a = sqrt(sum_k s_k / m) (the radius of gyration) empties the
        centre and keeps every weight >= 0; ``spread`` sets a, and then weights may be
        negative (a = 1 m if the body has rotary inertia but no mass)."""
        s = self.second_moments
        total = float(s.sum())
        if spread is None:
            spread = math.sqrt(total / self.mass) if self.mass > 0.0 and total > 0.0 else 1.0
        a = float(spread)
        if not a > 0.0:
            raise ValueError(f"spread must be > 0 (got {a})")
        c = np.array(self.offset)
        w = np.empty(7)
        d = np.tile(c, (7, 1))
        w[0] = self.mass - total / a**2
        for k in range(3):
            for j, sign in enumerate((1.0, -1.0)):
                w[1 + 2 * k + j] = s[k] / (2.0 * a**2)
                d[1 + 2 * k + j, k] += sign * a
        return w, d

    # ------------------------------------------------------------ ANCF
    def ancf_terms(self, F, q8, v8, a8, gravity):
        """(force8, M (8x8), K (8x8), T, V) of the body on the tip node's 8 coordinates.

        force8 = M a8 - Q_v - Q_g (N, N m: inertia minus applied force), M the body's mass
        matrix, K = -dQ_g/dq8 the gravity load stiffness, T the kinetic and
        V = -m g.(r0 + R c) the gravity potential energy (J). See :func:`ancf_tip_body_terms`."""
        args = [np.ascontiguousarray(a, dtype=np.float64) for a in (F, q8, v8, a8, gravity)]
        params = self.params()
        force = np.zeros(8)
        M = np.zeros((8, 8))
        K = np.zeros((8, 8))
        T, V = ancf_tip_body_terms(params, *args, 1.0, 0.0, force, M)
        ancf_tip_body_terms(params, *args, 0.0, 1.0, np.zeros(8), K)
        return force, M, K, T, V

    def ancf_frame(self, F, q8, v8):
        """R (3x3, global [tau m n]) and omega (3, section frame) of the tip section."""
        F = np.asarray(F, dtype=float)
        q8 = np.asarray(q8, dtype=float)
        v8 = np.asarray(v8, dtype=float)
        U = F.T @ q8[3:6]
        T, m, n = section_frame(U, float(q8[6]))
        _, w0, w1, w2 = strain_measures(U, F.T @ v8[3:6], float(q8[6]), float(v8[6]))
        return F @ np.column_stack([T, m, n]), np.array([w0, w1, w2])

    def ancf_momentum_about_axis(self, F, q8, v8, axis_point=(0.0, 0.0, 0.0), axis=(0.0, -1.0, 0.0)) -> float:
        """Angular momentum of the body about the line through ``axis_point`` along ``axis``
        (N m s; default: the hub axis, through the origin along -j0, positive in the sense of
        increasing hub angle): axis . ((r_cm - P) x m v_cm + R J omega)."""
        R, omega = self.ancf_frame(F, q8, v8)
        c = np.array(self.offset)
        q8 = np.asarray(q8, dtype=float)
        v8 = np.asarray(v8, dtype=float)
        r_cm = q8[0:3] + R @ c
        v_cm = v8[0:3] + R @ np.cross(omega, c)
        lever = r_cm - np.asarray(axis_point, dtype=float)
        H = self.mass * np.cross(lever, v_cm) + R @ (np.array(self.inertia) * omega)
        e = np.asarray(axis, dtype=float)
        return float(e @ H / np.linalg.norm(e))


@njit(cache=True, error_model="numpy")
def tip_kinematics(F, q8, v8, Z, e, G, H, hessian, Rg):
    """Orientation and angular velocity of the tip section from its node's coordinates.

    Fills Z = (F^T r0', F^T r0'dot, theta_1, theta_1dot); calls strain_jet on Z, so that
    e[1:4] = omega (section frame), G[i + 1, _VI[k]] = B[i, k], G[i + 1, _XI[k]] =
    d omega_i / dX_k, and (when ``hessian``) H[i + 1, _VI[l], _XI[k]] = dB[i, l] / dX_k;
    Rg = F [tau m n] (global components)."""
    U = np.empty(3)
    for i in range(3):
        Z[i] = F[0, i] * q8[3] + F[1, i] * q8[4] + F[2, i] * q8[5]
        Z[3 + i] = F[0, i] * v8[3] + F[1, i] * v8[4] + F[2, i] * v8[5]
        U[i] = Z[i]
    Z[PHI] = q8[6]
    Z[PSI] = v8[6]
    strain_jet(Z, e, G, H, hessian)
    T, m, n = section_frame(U, q8[6])
    for a in range(3):
        Rg[a, 0] = F[a, 0] * T[0] + F[a, 1] * T[1] + F[a, 2] * T[2]
        Rg[a, 1] = F[a, 0] * m[0] + F[a, 1] * m[1] + F[a, 2] * m[2]
        Rg[a, 2] = F[a, 0] * n[0] + F[a, 1] * n[1] + F[a, 2] * n[2]


@njit(cache=True, error_model="numpy")
def has_tip_body(params):
    """Whether :meth:`TipBody.params` ``params`` describe a body (a mass or an inertia); the
    parameters of no body are zeros."""
    return params[0] > 0.0 or params[1] > 0.0 or params[2] > 0.0 or params[3] > 0.0


@njit(cache=True, error_model="numpy")
def ancf_tip_body_terms(params, F, q8, v8, a8, gravity, coef_m, coef_k, force8, block):
    """Add the tip body's generalized force and iteration matrix to a tip node's rows.

    params: float64[7] = [m, J_tau, J_m, J_n, c_tau, c_m, c_n] (:meth:`TipBody.params`);
    F: the chart (3, 3); q8, v8, a8: the tip node's coordinates [r0, r0', theta_1,
    theta_1'] (global) and their first and second time derivatives; gravity (3,) m/s^2.
    ADDS M_tb a8 - Q_v - Q_g to force8 (8,) (the sign of the residual rows
    "M q'' + f_int - Q"; unscaled) and, when ``block`` is 8 x 8, ADDS coef_m M_tb + coef_k K_tb
    (K_tb = -dQ_g/dq8; inertia-force derivatives left out, see the module docstring).
    Returns (T, V): kinetic energy and gravity potential -m g.(r0 + R c) (J).
    """
    mass = params[0]
    J0, J1, J2 = params[1], params[2], params[3]
    c0, c1, c2 = params[4], params[5], params[6]
    want_block = block.shape[0] == 8 and block.shape[1] == 8
    want_k = want_block and coef_k != 0.0
    Z = np.empty(8)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    Rg = np.empty((3, 3))
    tip_kinematics(F, q8, v8, Z, e, G, H, want_k, Rg)
    om0, om1, om2 = e[1], e[2], e[3]

    # omega_dot = B Xddot + (d omega / dX) Xdot
    B = np.empty((3, 4))
    Xa = np.empty(4)
    for i in range(3):
        Xa[i] = F[0, i] * a8[3] + F[1, i] * a8[4] + F[2, i] * a8[5]
    Xa[3] = a8[6]
    wd = np.empty(3)
    for i in range(3):
        acc = 0.0
        for k in range(4):
            B[i, k] = G[i + 1, _VI[k]]
            acc += G[i + 1, _XI[k]] * Z[_VI[k]] + B[i, k] * Xa[k]
        wd[i] = acc

    # acceleration of the centre of mass relative to p, section frame: wd x c + w x (w x c)
    wc0 = om1 * c2 - om2 * c1
    wc1 = om2 * c0 - om0 * c2
    wc2 = om0 * c1 - om1 * c0
    ar0 = wd[1] * c2 - wd[2] * c1 + om1 * wc2 - om2 * wc1
    ar1 = wd[2] * c0 - wd[0] * c2 + om2 * wc0 - om0 * wc2
    ar2 = wd[0] * c1 - wd[1] * c0 + om0 * wc1 - om1 * wc0
    # translation: f_r = m (a_cm - g), global; and its section components fs = R^T f_r
    fr = np.empty(3)
    energy = 0.0
    potential = 0.0
    for a in range(3):
        fr[a] = mass * (a8[a] + Rg[a, 0] * ar0 + Rg[a, 1] * ar1 + Rg[a, 2] * ar2 - gravity[a])
        vcm = v8[a] + Rg[a, 0] * wc0 + Rg[a, 1] * wc1 + Rg[a, 2] * wc2
        energy += 0.5 * mass * vcm * vcm
        potential -= mass * gravity[a] * (q8[a] + Rg[a, 0] * c0 + Rg[a, 1] * c1 + Rg[a, 2] * c2)
    energy += 0.5 * (J0 * om0 * om0 + J1 * om1 * om1 + J2 * om2 * om2)
    fs0 = Rg[0, 0] * fr[0] + Rg[1, 0] * fr[1] + Rg[2, 0] * fr[2]
    fs1 = Rg[0, 1] * fr[0] + Rg[1, 1] * fr[1] + Rg[2, 1] * fr[2]
    fs2 = Rg[0, 2] * fr[0] + Rg[1, 2] * fr[1] + Rg[2, 2] * fr[2]
    # rotation about the centre of mass plus the moment of f_r about p: h (section frame)
    h0 = J0 * wd[0] + (J2 - J1) * om1 * om2 + c1 * fs2 - c2 * fs1
    h1 = J1 * wd[1] + (J0 - J2) * om2 * om0 + c2 * fs0 - c0 * fs2
    h2 = J2 * wd[2] + (J1 - J0) * om0 * om1 + c0 * fs1 - c1 * fs0
    QX = np.empty(4)
    for k in range(4):
        QX[k] = B[0, k] * h0 + B[1, k] * h1 + B[2, k] * h2
    for a in range(3):
        force8[a] += fr[a]
        force8[3 + a] += F[a, 0] * QX[0] + F[a, 1] * QX[1] + F[a, 2] * QX[2]
    force8[6] += QX[3]
    if not want_block:
        return energy, potential

    Mx = np.empty((4, 4))
    Mg = np.empty((4, 4))
    if coef_m != 0.0:
        # J_p = J + m (|c|^2 I - c c^T)
        cc = c0 * c0 + c1 * c1 + c2 * c2
        Jp = np.empty((3, 3))
        for i in range(3):
            ci = params[4 + i]
            for j in range(3):
                Jp[i, j] = -mass * ci * params[4 + j]
            Jp[i, i] += params[1 + i] + mass * cc
        for r in range(4):
            for s in range(r, 4):
                acc = 0.0
                for i in range(3):
                    for j in range(3):
                        acc += B[i, r] * Jp[i, j] * B[j, s]
                Mx[r, s] = acc
                Mx[s, r] = acc
        _add_x_block(F, Mx, coef_m, Mg, block)
        # r0 - X coupling: column k is m R (B_k x c) (chart X), then columns to global
        Mrx = np.empty((3, 4))
        for k in range(4):
            x0 = B[1, k] * c2 - B[2, k] * c1
            x1 = B[2, k] * c0 - B[0, k] * c2
            x2 = B[0, k] * c1 - B[1, k] * c0
            for a in range(3):
                Mrx[a, k] = mass * (Rg[a, 0] * x0 + Rg[a, 1] * x1 + Rg[a, 2] * x2)
        for a in range(3):
            block[a, a] += coef_m * mass
            for b in range(3):
                val = coef_m * (Mrx[a, 0] * F[b, 0] + Mrx[a, 1] * F[b, 1] + Mrx[a, 2] * F[b, 2])
                block[a, 3 + b] += val
                block[3 + b, a] += val
            block[a, 6] += coef_m * Mrx[a, 3]
            block[6, a] += coef_m * Mrx[a, 3]
    if want_k and mass != 0.0:
        # s = R^T g, u = c x s (section frame)
        s0 = Rg[0, 0] * gravity[0] + Rg[1, 0] * gravity[1] + Rg[2, 0] * gravity[2]
        s1 = Rg[0, 1] * gravity[0] + Rg[1, 1] * gravity[1] + Rg[2, 1] * gravity[2]
        s2 = Rg[0, 2] * gravity[0] + Rg[1, 2] * gravity[1] + Rg[2, 2] * gravity[2]
        u0 = c1 * s2 - c2 * s1
        u1 = c2 * s0 - c0 * s2
        u2 = c0 * s1 - c1 * s0
        for k in range(4):
            # c x (s x B_k)
            t0 = s1 * B[2, k] - s2 * B[1, k]
            t1 = s2 * B[0, k] - s0 * B[2, k]
            t2 = s0 * B[1, k] - s1 * B[0, k]
            y0 = c1 * t2 - c2 * t1
            y1 = c2 * t0 - c0 * t2
            y2 = c0 * t1 - c1 * t0
            for l in range(4):
                dB = H[1, _VI[l], _XI[k]] * u0 + H[2, _VI[l], _XI[k]] * u1 + H[3, _VI[l], _XI[k]] * u2
                Mx[l, k] = -mass * (dB + B[0, l] * y0 + B[1, l] * y1 + B[2, l] * y2)
        # K_X is a Hessian (symmetric); keep it exactly so for the symmetric chart-to-global map
        for l in range(4):
            for k in range(l + 1, 4):
                sym = 0.5 * (Mx[l, k] + Mx[k, l])
                Mx[l, k] = sym
                Mx[k, l] = sym
        _add_x_block(F, Mx, coef_k, Mg, block)
    return energy, potential


@njit(cache=True)
def _add_x_block(F, Mx, coef, Mg, block):
    """ADD coef times the symmetric 4 x 4 matrix Mx on X = (U, theta_1) (chart components), mapped
    to the tip node's global (r0', theta_1) rows and columns, to ``block`` (Mg: 4 x 4 work space)."""
    mass_to_global(F, Mx, Mg)
    for r in range(4):
        for s in range(4):
            block[_QX[r], _QX[s]] += coef * Mg[r, s]


# ================================================================ compiled terms: the kind "tip bodies"
class TipBodies(NamedTuple):
    """The tip bodies on ANCF tip nodes of a system, one row each."""

    index: np.ndarray  # int64 (n,): the beam's place among all beams (its chart, its energy row)
    x0: np.ndarray  # int64 (n,): where the tip node's 8 coordinates start in x
    params: np.ndarray  # (n, 7) TipBody.params()


def pack_tip_bodies(system, layout) -> TipBodies | None:
    """The :class:`TipBodies` of ``system`` placed by ``layout`` (None without any)."""
    rows = [(k, layout.beam_x(k).start + part.tip_node().start, part.tip_body.params())
            for k, part in enumerate(system.beams) if part.tip_body is not None and part.tip_node() is not None]
    if not rows:
        return None
    return TipBodies(np.array([r[0] for r in rows], dtype=np.int64), np.array([r[1] for r in rows], dtype=np.int64),
                     np.array([r[2] for r in rows], dtype=float).reshape(len(rows), 7))


def tip_body_equations(pack, ctx, F, x, v, acc, lam, t, coef_m, coef_c, coef_k, scale, load_factor, exact_stiffness,
                       want_matrix, res, ab, brow, bcol, bb):
    """Every tip body's rows (:func:`ancf_tip_body_terms`) on its tip node's coordinates
    (:mod:`hubbeam.system.terms`); gravity scaled by ``load_factor``."""
    zx = ctx.z_of_x
    g = np.empty(3)
    for i in range(3):
        g[i] = load_factor * ctx.gravity[i]
    force8 = np.empty(8)
    nb8 = 8 if want_matrix else 0
    block8 = np.empty((nb8, nb8))
    for k in range(pack.index.shape[0]):
        x0 = pack.x0[k]
        force8[:] = 0.0
        block8[:, :] = 0.0
        ancf_tip_body_terms(pack.params[k], F[pack.index[k]], x[x0 : x0 + 8], v[x0 : x0 + 8], acc[x0 : x0 + 8], g,
                            coef_m, coef_k, force8, block8)
        for i in range(8):
            res[zx[x0 + i]] += coef_k * force8[i]
        if want_matrix:
            for i in range(8):
                for j in range(8):
                    add_entry(ab, brow, bcol, bb, ctx.ku, zx[x0 + i], zx[x0 + j], block8[i, j])
    return 2.0, 0.0


def tip_body_energies(pack, ctx, F, x, v, beams):
    """Each tip body's kinetic and gravity energy, into its beam's row (J)."""
    zero8 = np.zeros(8)
    force8 = np.empty(8)
    no_block = np.empty((0, 0))
    for k in range(pack.index.shape[0]):
        x0 = pack.x0[k]
        i = pack.index[k]
        kinetic, potential = ancf_tip_body_terms(pack.params[k], F[i], x[x0 : x0 + 8], v[x0 : x0 + 8], zero8,
                                                 ctx.gravity, 0.0, 0.0, force8, no_block)
        terms.add_beam_energy(beams, i, kinetic, 0.0, potential)
    return 0.0, 0.0, 0.0


def tip_body_momenta(pack, ctx, F, x, v, out):
    """Each tip body's mass, first moment m r_cm, linear momentum m v_cm and angular momentum
    about the origin r_cm x m v_cm + R J omega (:mod:`hubbeam.system.terms`)."""
    Z = np.empty(8)
    e = np.empty(4)
    G = np.empty((4, 8))
    H = np.empty((4, 8, 8))
    Rg = np.empty((3, 3))
    r_cm, v_cm, wc, Jw = np.empty(3), np.empty(3), np.empty(3), np.empty(3)
    for k in range(pack.index.shape[0]):
        x0 = pack.x0[k]
        prm = pack.params[k]
        m = prm[0]
        tip_kinematics(F[pack.index[k]], x[x0:x0 + 8], v[x0:x0 + 8], Z, e, G, H, False, Rg)
        om0, om1, om2 = e[1], e[2], e[3]
        c0, c1, c2 = prm[4], prm[5], prm[6]
        wc[0] = om1 * c2 - om2 * c1
        wc[1] = om2 * c0 - om0 * c2
        wc[2] = om0 * c1 - om1 * c0
        Jw[0] = prm[1] * om0
        Jw[1] = prm[2] * om1
        Jw[2] = prm[3] * om2
        for i in range(3):
            r_cm[i] = x[x0 + i] + Rg[i, 0] * c0 + Rg[i, 1] * c1 + Rg[i, 2] * c2
            v_cm[i] = v[x0 + i] + Rg[i, 0] * wc[0] + Rg[i, 1] * wc[1] + Rg[i, 2] * wc[2]
        out[0] += m
        for i in range(3):
            out[1 + i] += m * r_cm[i]
            out[4 + i] += m * v_cm[i]
            out[7 + i] += Rg[i, 0] * Jw[0] + Rg[i, 1] * Jw[1] + Rg[i, 2] * Jw[2]
        out[7] += m * (r_cm[1] * v_cm[2] - r_cm[2] * v_cm[1])
        out[8] += m * (r_cm[2] * v_cm[0] - r_cm[0] * v_cm[2])
        out[9] += m * (r_cm[0] * v_cm[1] - r_cm[1] * v_cm[0])


KIND = terms.register(TipBodies, pack_tip_bodies, tip_body_equations, tip_body_energies,
                      bandwidth=lambda system, layout: 7,  # the tip node's 8 x 8 block
                      momenta=tip_body_momenta)
