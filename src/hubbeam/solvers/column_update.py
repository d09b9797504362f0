"""Refreshing the joint angles' columns of a kept Newton matrix without refactorising it.

A beam on a hinge keeps its Newton matrix for only ten to twenty steps where the same beam
clamped keeps one for a whole run: the joint angle psi and the beam's elastic coordinates
nearly overlap (turning the hinge by psi while bending the beam back by psi moves only the
root element), and the matrix's entries that couple psi to the beam change by about 1 % per
step as the beam vibrates (docs/benchmarks.md, case J). What goes stale is psi's column
(and, by the symmetry of the inertia coupling, its row); the rest of the matrix stays good
for hundreds of steps.

So when a kept matrix goes stale (a step needed more than ``refresh_iterations``), the next
step patches it: the joint angles' columns J of the kept matrix A become the residual's
forward differences C along those coordinates (one residual per joint angle, at the step's
predictor), and their rows change by the transpose of the columns' change U = C - A E (E: the
columns e_J of the identity; the change of the code's matrix in psi's row and column is the
inertia coupling's, symmetric: measured equal to 1e-16). The patched matrix

    A + U E^T + E Ut^T,   Ut = U with its rows J zeroed (the J x J block changes once),

is solved by the Sherman-Morrison-Woodbury formula on the kept factors of A: with
P = [U, E], Q = [E, Ut], A^-1 P = [G - E, H], G = A^-1 C, H = A^-1 E (2k solves) and the
capacitance K = I + Q^T A^-1 P = [[G_J, H_J], [Ut^T G, I + Ut^T H]] (2k x 2k),

    (A + P Q^T)^-1 b = y - [G - E, H] K^-1 [y_J, Ut^T y],   y = A^-1 b.

The residual is exact, so the step converges to the same tolerance whatever its iteration
matrix; the patch only changes how fast. On the nodal FFR exp1 beam on a stiff flap hinge
(``python benchmarks/joint_cost.py columns``) the spectral radius of I - B^-1 D (D the exact
tangent, B the kept matrix) with B from 10 steps before is 6.5e-2; patched in psi's column
alone 3.3e-3, in its column and row 6.5e-4 (30 steps: 2.0e-1, 9.7e-3, 1.6e-3). A patch always
changes the factorised matrix A (not an earlier patch), so patches do not pile up. The
controller (:func:`hubbeam.solvers.newton_control.newton_decide`) asks for a patch, and
falls back to refactorising when a patched matrix does not bring the step back to two
iterations.

A patch also goes stale, and fast: on the 4-mode FFR exp1 beam on that hinge, in its first
seconds, the exact tangent (the residual's differences) moves steadily in the hub and joint
angles' rows and columns, by at most 3.9e-5 in one step and 7.9e-5 in two, and a patch kept
from one step before contracted at a median 4.2e-3 against 8.2e-4 at the step that made it
(a new code matrix, whose tangent leaves out the rates' derivatives: 1.1e-3). The first
increments there, 3.6e-6, are large (the hinge angle's acceleration swings through +-18 rad/s^2
with a period of about 6 steps, which no predictor of the acceleration follows), a step then
converges in two iterations only below a rate of about 2e-3, and the step after each patch took
a third iteration. So the patch drifts: a patch made while the factors carry the one before
(no factorisation between them, ``steps`` steps apart) records the change per step of G =
A^-1 C and of Ut (both linear in C), and each later step on the same patch extrapolates them,
G = G_p + age dG, Ut = Ut_p + age dUt (C linear in time since the patch), and recomputes only
the capacitance (:func:`record_drift`, :func:`drifted`): no residual, no solve. A carried
patch then contracts at a median 1.4e-3, and over 10 s the third iterations fell from 0.096
to 0.032 per step and the patches from 0.095 to 0.031 (``python benchmarks/joint_cost.py
stale``; docs/benchmarks.md, case J).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from hubbeam.system.assembly import dense_inverse

#: the forward difference step of a joint angle's column (rad, times max(1, |psi|)): about the
#: square root of the machine epsilon, where truncation and round-off errors of a forward
#: difference balance
DIFFERENCE_STEP = 1.5e-8


def joint_columns(layout, update: bool = True) -> np.ndarray:
    """The x indices of every beam's joint angles (int64; empty for a system without joints,
    or without ``update``): the columns a column update refreshes."""
    if not update:
        return np.zeros(0, dtype=np.int64)
    return np.array([i for k in range(layout.beams) for i in range(layout.nx)[layout.joint_x(k)]], dtype=np.int64)


@njit(cache=True)
def difference_step(x):
    """The forward difference step at coordinate value x (exactly representable: (x + d) - x == d)."""
    d = DIFFERENCE_STEP * max(1.0, abs(x))
    return (x + d) - x


@njit(cache=True)
def matrix_column(ab, brow, bcol, bb, bw, j, out):
    """Column j of a bordered band matrix into ``out`` (the storage of
    :class:`~hubbeam.system.assembly.BorderedBandMatrix`, the diagonal at row 2 bw of ``ab``),
    before its factorisation."""
    nb = bb.shape[0]
    m = ab.shape[1]
    for i in range(nb + m):
        out[i] = 0.0
    if j < nb:
        for i in range(nb):
            out[i] = bb[i, j]
        for i in range(m):
            out[nb + i] = bcol[i, j]
        return
    c = j - nb
    for i in range(nb):
        out[i] = brow[i, c]
    for i in range(max(0, c - bw), min(m, c + bw + 1)):
        out[nb + i] = ab[2 * bw + i - c, c]


@njit(cache=True)
def column_change(C, kept, z_columns, Ut):
    """Ut = the rows' change (module docstring): C - A E (``C`` and ``kept`` = A E as k x n rows),
    its entries J zeroed."""
    for a in range(C.shape[0]):
        for i in range(C.shape[1]):
            Ut[a, i] = C[a, i] - kept[a, i]
        for b in range(z_columns.shape[0]):
            Ut[a, z_columns[b]] = 0.0


@njit(cache=True)
def unit_rows(H, z_columns):
    """H = E^T (k x n rows), to be solved in place into A^-1 E."""
    for a in range(H.shape[0]):
        for i in range(H.shape[1]):
            H[a, i] = 0.0
        H[a, z_columns[a]] = 1.0


@njit(cache=True)
def capacitance(G, H, Ut, z_columns, S, K_inverse):
    """The inverse of the capacitance K (module docstring; G = A^-1 C and H = A^-1 E as k x n
    rows) into ``K_inverse`` (2k x 2k; ``S`` 2k x 2k scratch). Returns 0, or -1 when the
    patched matrix is singular."""
    k = z_columns.shape[0]
    n = G.shape[1]
    for a in range(k):
        for b in range(k):
            S[a, b] = G[b, z_columns[a]]
            S[a, k + b] = H[b, z_columns[a]]
            g = 0.0
            h = 1.0 if a == b else 0.0
            for i in range(n):
                g += Ut[a, i] * G[b, i]
                h += Ut[a, i] * H[b, i]
            S[k + a, b] = g
            S[k + a, k + b] = h
    return dense_inverse(S, K_inverse)


@njit(cache=True)
def patch_solve(G, H, Ut, K_inverse, z_columns, y, w, s):
    """Turn y = A^-1 b (in place) into the solution of the patched matrix (module docstring;
    ``w``, ``s``: 2k scratch)."""
    k = z_columns.shape[0]
    n = y.shape[0]
    for a in range(k):
        w[a] = y[z_columns[a]]
        acc = 0.0
        for i in range(n):
            acc += Ut[a, i] * y[i]
        w[k + a] = acc
    for a in range(2 * k):
        acc = 0.0
        for b in range(2 * k):
            acc += K_inverse[a, b] * w[b]
        s[a] = acc
    for a in range(k):
        for i in range(n):
            y[i] -= G[a, i] * s[a] + H[a, i] * s[k + a]
    for a in range(k):
        y[z_columns[a]] += s[a]


@njit(cache=True)
def record_drift(G, Ut, G_last, Ut_last, G_drift, Ut_drift, steps):
    """At a new patch (``G`` = A^-1 C and ``Ut`` as k x n rows): with ``steps`` > 0, the
    change per step of both since the last patch on the same factors (``G_last``,
    ``Ut_last``, made ``steps`` steps before) into ``G_drift``, ``Ut_drift``; then the new
    patch becomes the last (module docstring)."""
    for a in range(G.shape[0]):
        for i in range(G.shape[1]):
            if steps > 0:
                G_drift[a, i] = (G[a, i] - G_last[a, i]) / steps
                Ut_drift[a, i] = (Ut[a, i] - Ut_last[a, i]) / steps
            G_last[a, i] = G[a, i]
            Ut_last[a, i] = Ut[a, i]


@njit(cache=True)
def drifted(G_last, Ut_last, G_drift, Ut_drift, age, G, Ut):
    """The patch ``age`` steps after it was made, extrapolated linearly (module docstring):
    G = G_last + age G_drift, Ut = Ut_last + age Ut_drift."""
    for a in range(G.shape[0]):
        for i in range(G.shape[1]):
            G[a, i] = G_last[a, i] + age * G_drift[a, i]
            Ut[a, i] = Ut_last[a, i] + age * Ut_drift[a, i]


class PatchedMatrix:
    """An iteration matrix (:class:`hubbeam.solvers.generalized_alpha.IterationMatrix`, with
    its ``columns`` kept) whose columns ``z_columns`` become ``columns`` (n x k, in z) and whose
    rows ``z_columns`` change by their transpose (module docstring), solved by the
    Sherman-Morrison-Woodbury formula on the factors of the original. Raises numpy's
    LinAlgError when the patched matrix is singular."""

    def __init__(self, base, columns: np.ndarray, z_columns: np.ndarray) -> None:
        self.base, self.z_columns = base, z_columns
        self.h, self.chart = base.h, base.chart
        k, n = z_columns.shape[0], columns.shape[0]
        C = np.ascontiguousarray(columns.T)
        self.Ut = np.empty((k, n))
        column_change(C, base.columns, z_columns, self.Ut)
        self.G = np.array([base.solve(C[a]) for a in range(k)]).reshape(k, n)
        H = np.empty((k, n))
        unit_rows(H, z_columns)
        self.H = np.array([base.solve(H[a]) for a in range(k)]).reshape(k, n)
        self.G_last, self.Ut_last = self.G.copy(), self.Ut.copy()
        self.G_drift, self.Ut_drift = np.zeros((k, n)), np.zeros((k, n))
        self.K_inverse = np.empty((2 * k, 2 * k))
        self._capacitance()

    def _capacitance(self) -> None:
        k = self.z_columns.shape[0]
        if capacitance(self.G, self.H, self.Ut, self.z_columns, np.empty((2 * k, 2 * k)), self.K_inverse) != 0:
            raise np.linalg.LinAlgError("the patched iteration matrix is singular")

    def follow(self, previous: PatchedMatrix, steps: int) -> None:
        """Record the drift per step since ``previous``, a patch of the same factors made
        ``steps`` steps before (:func:`record_drift`). ``previous`` is left as it was."""
        self.G_last, self.Ut_last = previous.G_last.copy(), previous.Ut_last.copy()
        record_drift(self.G, self.Ut, self.G_last, self.Ut_last, self.G_drift, self.Ut_drift, steps)

    def drift(self, age: int) -> None:
        """This patch ``age`` steps after it was made (:func:`drifted`); raises numpy's
        LinAlgError when the drifted matrix is singular."""
        drifted(self.G_last, self.Ut_last, self.G_drift, self.Ut_drift, age, self.G, self.Ut)
        self._capacitance()

    def valid_for(self, h: float, chart: np.ndarray) -> bool:
        return self.base.valid_for(h, chart)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        y = np.array(self.base.solve(rhs), dtype=float)
        k = self.z_columns.shape[0]
        patch_solve(self.G, self.H, self.Ut, self.K_inverse, self.z_columns, y, np.empty(2 * k), np.empty(2 * k))
        return y
