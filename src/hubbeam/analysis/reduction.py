"""Reduced linear models: modal truncation with residualisation, and balanced reduction of the
stable part.

The eigenvalues lambda of A fall into four kinds (:func:`spectrum`):

- **rigid**: the model's rigid-body modes (the free hub's rotation: the ``rigid_modes``
  eigenvalue pairs nearest zero, as :meth:`LinearModel.modal_summary` leaves them out) and
  anything below :data:`RIGID_TOL_HZ`;
- **unstable**: Re lambda > :data:`UNDAMPED_ZETA` |lambda|;
- **undamped**: |Re lambda| <= :data:`UNDAMPED_ZETA` |lambda| (no damping reaches the mode:
  no drag, no structural damping, or a mode the torque law's kd does not move);
- **stable**: Re lambda < -:data:`UNDAMPED_ZETA` |lambda|.

A mode is *invisible* when no input reaches it or no output sees it: the cosine between its
left eigenvector and every column of B, or between its right eigenvector and every row of C,
is below :data:`VISIBLE_COSINE` (round-off: the spacecraft's symmetric panel modes, which a hub
torque cannot excite, give 1e-11 and less; its weakest visible mode 4e-5). An invisible mode
adds nothing to the transfer function. Modes whose eigenvalues agree to
:data:`CLUSTER_RTOL` (the same mode of two identical beams) are one cluster: kept or dropped
together, visible if one of them is.

The model is split with an ordered real Schur form A = Z T Z^T and a Sylvester equation
(T11 X - X T22 = -T12) into decoupled blocks, block-diagonal [[T11, 0], [0, T22]] in the
coordinates Z [[I, X], [0, I]] (Golub and Van Loan, Sec. 7.6): the kept poles are exactly the
full model's eigenvalues (to the Schur form's round-off). A dropped block (A2, B2, C2) is
*residualised*: its states take their steady value for the current input, which adds
-C2 A2^-1 B2 to D, so the DC gain of everything but the rigid and unstable modes is the full
model's. Kept blocks of modes are written in real modal form: one state for a real
eigenvalue, and for a complex pair sigma +- i omega the two states (``_re``, ``_im``) of the
block [[sigma, omega], [-omega, sigma]].

- :func:`modal_reduction` (``linearize --reduce N``, ``--fmax F``): rigid and unstable modes
  kept as they are; of the other visible modes the N lowest (by |lambda|) and none above F Hz;
  the rest residualised.
- :func:`balanced_reduction` (``linearize --balanced N``): the stable part (its
  invisible modes and, with ``fmax``, the modes above F residualised first) brought to
  balanced form by the square-root method (Laub et al. 1987; Lyapunov equations by
  Bartels-Stewart, :func:`scipy.linalg.solve_continuous_lyapunov`: python-control's
  ``balred`` and ``hsvd`` need slycot), its Hankel singular values sigma_1 >= sigma_2 >= ...,
  and N balanced states kept. The discarded balanced states are residualised (the singular
  perturbation approximation of Liu and Anderson 1989: the DC gain kept, the same bound as
  truncation) or truncated (``match="truncate"``: exact at infinite frequency); either way
  ||G_stable - G_reduced||_inf <= 2 sum of the discarded sigma_i. Rigid, unstable and visible
  undamped modes are kept as they are (a Gramian needs asymptotic stability).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np
import scipy.linalg

#: below this frequency (Hz) a mode is rigid (the rule of :func:`hubbeam.solvers.modal.modal_analysis`)
RIGID_TOL_HZ = 1e-3
#: a mode whose damping ratio is below this (in size) counts as undamped (round-off gives the
#: undamped modes of the bundled models 1e-12 and less)
UNDAMPED_ZETA = 1e-10
#: a mode no input reaches or no output sees to this cosine is invisible (see the module doc)
VISIBLE_COSINE = 1e-8
#: eigenvalues equal to this relative tolerance form one cluster
CLUSTER_RTOL = 1e-6
#: the largest coupling ||X|| of a Schur split that still separates two groups of modes well
MAX_COUPLING = 1e8


class ModeKind(Enum):
    RIGID = "rigid"
    UNSTABLE = "unstable"
    UNDAMPED = "undamped"
    STABLE = "stable"


@dataclass
class Spectrum:
    """The eigenvalues of A with their kind, visibility and cluster (see the module doc)."""

    values: np.ndarray  # complex
    kinds: list[ModeKind]
    visible: np.ndarray  # bool
    cluster: np.ndarray  # int: eigenvalues with the same number are one cluster

    def modes(self) -> list[list[int]]:
        """The modes as lists of eigenvalue indices: a real eigenvalue alone, a complex pair
        together, ascending in |lambda|."""
        s = self.values
        up = [i for i in range(s.size) if s[i].imag >= 0.0]
        down = [i for i in range(s.size) if s[i].imag < 0.0]
        modes = []
        for i in up:
            if s[i].imag == 0.0:
                modes.append([i])
            else:
                j = min(down, key=lambda j: abs(s[j] - np.conj(s[i])))
                down.remove(j)
                modes.append([i, j])
        return sorted(modes, key=lambda m: abs(s[m[0]]))


def spectrum(A, B, C, rigid_modes: int = 0) -> Spectrum:
    """Eigenvalues of A, each with its :class:`ModeKind`, its visibility from the inputs B and
    outputs C, and its cluster."""
    s, left, right = scipy.linalg.eig(A, left=True, right=True)
    n = s.size
    size = np.abs(s)
    rigid = np.zeros(n, dtype=bool)
    rigid[np.argsort(size)[: 2 * rigid_modes]] = True
    rigid |= size / (2 * np.pi) < RIGID_TOL_HZ
    kinds = []
    for i in range(n):
        if rigid[i]:
            kinds.append(ModeKind.RIGID)
        elif s[i].real > UNDAMPED_ZETA * size[i]:
            kinds.append(ModeKind.UNSTABLE)
        elif s[i].real >= -UNDAMPED_ZETA * size[i]:
            kinds.append(ModeKind.UNDAMPED)
        else:
            kinds.append(ModeKind.STABLE)
    B, C = np.atleast_2d(B), np.atleast_2d(C)
    b_norms = np.maximum(np.linalg.norm(B, axis=0), 1e-300)
    c_norms = np.maximum(np.linalg.norm(C, axis=1), 1e-300)
    reach = (np.abs(left.conj().T @ B) / b_norms).max(axis=1, initial=0.0) / np.linalg.norm(left, axis=0)
    seen = (np.abs(C @ right) / c_norms[:, None]).max(axis=0, initial=0.0) / np.linalg.norm(right, axis=0)
    # a model without inputs (or outputs) is judged by the other side alone
    visible = ((reach > VISIBLE_COSINE) | (B.shape[1] == 0)) & ((seen > VISIBLE_COSINE) | (C.shape[0] == 0))
    cluster = np.arange(n)
    order = np.argsort(size)
    for a, i in enumerate(order):  # equal eigenvalues are neighbours in |lambda|
        for j in order[a + 1:]:
            if size[j] > (1 + CLUSTER_RTOL) * size[i]:
                break
            if abs(s[i] - s[j]) <= CLUSTER_RTOL * size[j] and kinds[i] == kinds[j]:
                cluster[cluster == cluster[j]] = cluster[i]
    for c in np.unique(cluster):
        members = cluster == c
        visible[members] = visible[members].any()
    return Spectrum(s, kinds, visible, cluster)


@dataclass
class Block:
    """A decoupled part of a model: x_full contribution = V z, z' = A z + B u, y = C z."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    V: np.ndarray


def _predicate(values: np.ndarray, chosen: np.ndarray):
    """The Schur sort function that selects the eigenvalues ``chosen`` (a mask on ``values``):
    each eigenvalue the Schur form gives is matched to the nearest of ``values``."""
    def select(re, im):
        return bool(chosen[np.argmin(np.abs(values - complex(re, im)))])
    return select


def split(block: Block, values: np.ndarray, chosen: np.ndarray) -> tuple[Block, Block]:
    """(the chosen modes, the others) of ``block`` as two decoupled blocks (ordered real Schur
    form and a Sylvester equation, see the module doc). ``values``: the block's eigenvalues,
    ``chosen`` a mask on them that never splits a complex pair or a cluster."""
    n, k = block.A.shape[0], int(np.count_nonzero(chosen))
    if k == 0 or k == n:
        empty = Block(np.zeros((0, 0)), np.zeros((0, block.B.shape[1])), np.zeros((block.C.shape[0], 0)),
                      np.zeros((block.V.shape[0], 0)))
        return (block, empty) if k == n else (empty, block)
    T, Z, sdim = scipy.linalg.schur(block.A, output="real", sort=_predicate(values, chosen))
    if sdim != k:
        raise ValueError(f"the ordered Schur form selected {sdim} eigenvalues, not {k} (two groups of modes too close "
                         "to tell apart)")
    T11, T12, T22 = T[:k, :k], T[:k, k:], T[k:, k:]
    X = scipy.linalg.solve_sylvester(T11, -T22, -T12)
    if not np.all(np.isfinite(X)) or np.linalg.norm(X) > MAX_COUPLING * max(1.0, np.linalg.norm(T12)):
        raise ValueError(f"the kept and dropped modes are too close to decouple (coupling {np.linalg.norm(X):.3g}); "
                         "keep one mode more or less")
    Bz, Cz = Z.T @ block.B, block.C @ Z
    Vz = block.V @ Z
    first = Block(T11, Bz[:k] - X @ Bz[k:], Cz[:, :k], Vz[:, :k])
    second = Block(T22, Bz[k:], Cz[:, :k] @ X + Cz[:, k:], Vz[:, :k] @ X + Vz[:, k:])
    return first, second


def residual_gain(block: Block) -> np.ndarray:
    """-C A^-1 B: the steady output of a block for a unit input (what residualising it adds to D)."""
    if block.A.shape[0] == 0:
        return np.zeros((block.C.shape[0], block.B.shape[1]))
    return -block.C @ np.linalg.solve(block.A, block.B)


def modal_form(block: Block) -> tuple[Block, np.ndarray]:
    """The block in real modal form (one state per real eigenvalue, two per complex pair, in
    the order of ascending |lambda|) and its eigenvalues in that order (one per mode, Im >= 0);
    the block itself (and its eigenvalues) when its eigenvectors are too ill-conditioned
    (a defective eigenvalue) to diagonalise it."""
    n = block.A.shape[0]
    if n == 0:
        return block, np.zeros(0, dtype=complex)
    s, vectors = np.linalg.eig(block.A)
    order = sorted([i for i in range(n) if s[i].imag >= 0.0], key=lambda i: (abs(s[i]), s[i].imag))
    columns, values = [], []
    for i in order:
        v = vectors[:, i] / np.linalg.norm(vectors[:, i])
        v = v * np.exp(-1j * np.angle(v[np.argmax(np.abs(v))]))  # its largest entry real and positive
        columns += [v.real] if s[i].imag == 0.0 else [v.real, v.imag]
        values.append(s[i])
    S = np.column_stack(columns)
    if S.shape[1] != n or np.linalg.cond(S) > 1e10:
        return block, np.linalg.eigvals(block.A)
    Sinv = np.linalg.inv(S)
    A = Sinv @ block.A @ S
    A[np.abs(A) < 1e-14 * np.max(np.abs(A))] = 0.0  # the off-block entries are round-off
    return Block(A, Sinv @ block.B, block.C @ S, block.V @ S), np.array(values)


def mode_state_names(values: np.ndarray, first: int = 1) -> list[str]:
    """State names of a block in real modal form: ``modeJ`` (real) or ``modeJ_re``, ``modeJ_im``."""
    names = []
    for j, s in enumerate(values, first):
        names += [f"mode{j}"] if s.imag == 0.0 else [f"mode{j}_re", f"mode{j}_im"]
    return names


@dataclass
class Reduced:
    """A reduced model: (A, B, C, D), its state names, the projection V (the full model's
    states ~ V z, the residualised modes' steady part left out) and what was done (``info``,
    for the JSON, and ``notes``, one line each)."""

    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: list[str]
    V: np.ndarray
    info: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)


def _assemble(blocks: list[tuple[Block, list[str]]], D: np.ndarray, info: dict, notes: list[str]) -> Reduced:
    A = scipy.linalg.block_diag(*[b.A for b, _ in blocks])
    B = np.vstack([b.B for b, _ in blocks])
    C = np.hstack([b.C for b, _ in blocks])
    V = np.hstack([b.V for b, _ in blocks])
    return Reduced(A, B, C, D, [n for _, names in blocks for n in names], V, info, notes)


def _scaled(A, B, C) -> Block:
    """The model as one block after a diagonal similarity that balances A's rows and columns
    (:func:`scipy.linalg.matrix_balance`: exact powers of 2; the second-order form's position
    and velocity states differ by the frequencies, up to 1e5 rad/s), which conditions the
    Schur, Sylvester and Lyapunov steps."""
    _, (scale, _) = scipy.linalg.matrix_balance(A, permute=False, separate=True)
    return Block(A * (1.0 / scale)[:, None] * scale[None, :], B / scale[:, None], C * scale[None, :], np.diag(scale))


def _chosen_mask(spec: Spectrum, modes: list[list[int]]) -> np.ndarray:
    mask = np.zeros(spec.values.size, dtype=bool)
    for m in modes:
        mask[m] = True
    return mask


def _lowest(spec: Spectrum, candidates: list[list[int]], count: int | None, fmax: float | None, notes: list[str]
            ) -> list[list[int]]:
    """The ``count`` lowest of the ``candidates`` (modes) and none above ``fmax`` Hz, with a
    cluster never cut (one note when the count grows for it)."""
    s = spec.values
    kept = [m for m in candidates if fmax is None or abs(s[m[0]]) / (2 * np.pi) <= fmax]
    if count is not None and count < len(kept):
        last = kept[count - 1] if count > 0 else None
        take = count
        while last is not None and take < len(kept) and spec.cluster[kept[take][0]] == spec.cluster[last[0]]:
            take += 1
        if take > count:
            notes.append(f"mode {count} ({abs(s[last[0]]) / (2 * np.pi):.6g} Hz) has the frequency of the next "
                         f"{take - count} (identical beams): all {take} kept")
        kept = kept[:take]
    return kept


def _visible_undamped_and_stable(spec: Spectrum) -> tuple[list[list[int]], list[list[int]]]:
    """(visible modes that are neither rigid nor unstable, invisible ones), ascending."""
    shown, hidden = [], []
    for m in spec.modes():
        if spec.kinds[m[0]] in (ModeKind.RIGID, ModeKind.UNSTABLE):
            continue
        (shown if spec.visible[m[0]] else hidden).append(m)
    return shown, hidden


def _hz(spec: Spectrum, modes: list[list[int]]) -> str:
    f = sorted(abs(spec.values[m[0]]) / (2 * np.pi) for m in modes)
    return f"{f[0]:.4g} Hz" if len(f) == 1 else f"{f[0]:.4g} to {f[-1]:.4g} Hz"


def _kept_as_they_are(spec: Spectrum, full: Block, chosen: np.ndarray) -> tuple[Block, Block, Block]:
    """(rigid block, modal-form block of the chosen non-rigid modes, the dropped block) of ``full``."""
    kept, dropped = split(full, spec.values, chosen)
    values = np.linalg.eigvals(kept.A)
    rigid_mask = np.array([spec.kinds[int(np.argmin(np.abs(spec.values - v)))] is ModeKind.RIGID for v in values])
    rigid, moving = split(kept, values, rigid_mask)
    return rigid, moving, dropped


def modal_reduction(A, B, C, D, count: int | None = None, fmax: float | None = None, rigid_modes: int = 0
                    ) -> Reduced:
    """Modal truncation (see the module doc): rigid and unstable modes kept as they are, of
    the other visible modes the ``count`` lowest and none above ``fmax`` Hz; everything else
    residualised."""
    A, B, C, D = (np.asarray(M, dtype=float) for M in (A, B, C, D))
    spec = spectrum(A, B, C, rigid_modes)
    notes: list[str] = []
    shown, hidden = _visible_undamped_and_stable(spec)
    kept_modes = _lowest(spec, shown, count, fmax, notes)
    as_is = [m for m in spec.modes() if spec.kinds[m[0]] in (ModeKind.RIGID, ModeKind.UNSTABLE)]
    full = _scaled(A, B, C)
    rigid, moving, dropped = _kept_as_they_are(spec, full, _chosen_mask(spec, as_is + kept_modes))
    moving, values = modal_form(moving)
    Dr = D + residual_gain(dropped)
    residualised = [m for m in shown if m not in kept_modes]
    if hidden:
        notes.append(f"{len(hidden)} mode(s) that no input reaches or no output sees ({_hz(spec, hidden)}) left out")
    if residualised:
        notes.append(f"{len(residualised)} mode(s) ({_hz(spec, residualised)}) residualised: their steady response "
                     "is in D")
    unstable = [m for m in as_is if spec.kinds[m[0]] is ModeKind.UNSTABLE]
    if unstable:
        notes.append(f"{len(unstable)} unstable mode(s) kept as they are ({_hz(spec, unstable)})")
    info = {"method": "modal", "full_states": int(A.shape[0]), "kept_modes": len(kept_modes),
            "rigid_states": int(rigid.A.shape[0]), "residualised_modes": len(residualised),
            "invisible_modes": len(hidden), "kept_frequencies_hz": [float(abs(v) / (2 * np.pi)) for v in values]}
    blocks = [(rigid, [f"rigid{i + 1}" for i in range(rigid.A.shape[0])]), (moving, mode_state_names(values))]
    if moving.A.shape[0] and len(mode_state_names(values)) != moving.A.shape[0]:  # not diagonalisable: Schur block
        blocks[1] = (moving, [f"kept{i + 1}" for i in range(moving.A.shape[0])])
    return _assemble(blocks, Dr, info, notes)


def hankel_singular_values(A, B, C) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(sigma descending, Lc, Lo) of a stable (A, B, C): the Gramians P = Lc Lc^T (A P + P A^T
    + B B^T = 0) and Q = Lo Lo^T (A^T Q + Q A + C^T C = 0) by Bartels-Stewart, their square
    roots by symmetric eigendecomposition (semidefinite to round-off), sigma the singular
    values of Lo^T Lc."""
    P = scipy.linalg.solve_continuous_lyapunov(A, -B @ B.T)
    Q = scipy.linalg.solve_continuous_lyapunov(A.T, -C.T @ C)

    def root(G):
        w, U = np.linalg.eigh(0.5 * (G + G.T))
        return U * np.sqrt(np.clip(w, 0.0, None))

    Lc, Lo = root(P), root(Q)
    return np.linalg.svd(Lo.T @ Lc, compute_uv=False), Lc, Lo


def balanced_reduction(A, B, C, D, order: int, fmax: float | None = None, rigid_modes: int = 0,
                       match: str = "dc") -> Reduced:
    """Balanced reduction of the stable part to ``order`` states (see the module doc);
    ``match``: "dc" (residualise the discarded balanced states: the DC gain kept) or
    "truncate". ValueError when the model has no stable part."""
    if match not in ("dc", "truncate"):
        raise ValueError(f"match: 'dc' or 'truncate' (got {match!r})")
    A, B, C, D = (np.asarray(M, dtype=float) for M in (A, B, C, D))
    spec = spectrum(A, B, C, rigid_modes)
    notes: list[str] = []
    shown, hidden = _visible_undamped_and_stable(spec)
    above = [m for m in shown if fmax is not None and abs(spec.values[m[0]]) / (2 * np.pi) > fmax]
    stable = [m for m in shown if m not in above and spec.kinds[m[0]] is ModeKind.STABLE]
    undamped = [m for m in shown if m not in above and spec.kinds[m[0]] is ModeKind.UNDAMPED]
    as_is = [m for m in spec.modes() if spec.kinds[m[0]] in (ModeKind.RIGID, ModeKind.UNSTABLE)] + undamped
    if not stable:
        raise ValueError("the model has no stable part to balance (every mode is rigid, undamped or unstable: with no "
                         "damping, use the modal reduction)")
    full = _scaled(A, B, C)
    kept, dropped = split(full, spec.values, _chosen_mask(spec, as_is + stable))
    values = np.linalg.eigvals(kept.A)
    stable_mask = np.array([spec.kinds[int(np.argmin(np.abs(spec.values - v)))] is ModeKind.STABLE for v in values])
    part, rest = split(kept, values, stable_mask)
    rest_values = np.linalg.eigvals(rest.A)
    rigid_mask = np.array([spec.kinds[int(np.argmin(np.abs(spec.values - v)))] is ModeKind.RIGID
                           for v in rest_values])
    rigid, moving = split(rest, rest_values, rigid_mask)
    moving, moving_values = modal_form(moving)
    part, _ = modal_form(part)  # block-diagonal: each Lyapunov entry then couples two modes only
    sigma, Lc, Lo = hankel_singular_values(part.A, part.B, part.C)
    U, s_, Vt = np.linalg.svd(Lo.T @ Lc)
    minimal = int(np.count_nonzero(sigma > max(sigma[0], 1e-300) * part.A.shape[0] * 1e-14))
    if order > minimal:
        notes.append(f"the stable part has {minimal} states that the inputs reach and the outputs see (Hankel singular "
                     f"values above round-off): {minimal} kept, not {order}")
        order = minimal
    while 0 < order < minimal and sigma[order] > (1 - 1e-9) * sigma[order - 1]:
        order += 1  # equal Hankel singular values: keep them together
    # the minimal balanced realisation (square-root method), then its last states discarded
    scale = 1.0 / np.sqrt(sigma[:minimal])
    T = (Lc @ Vt[:minimal].T) * scale
    Ti = (U[:, :minimal].T @ Lo.T) * scale[:, None]
    Ab, Bb, Cb, Vb = Ti @ part.A @ T, Ti @ part.B, part.C @ T, part.V @ T
    k = order
    Dr = D + residual_gain(dropped)
    if match == "dc" and k < minimal:
        A22inv_A21 = np.linalg.solve(Ab[k:, k:], Ab[k:, :k])
        A22inv_B2 = np.linalg.solve(Ab[k:, k:], Bb[k:])
        balanced = Block(Ab[:k, :k] - Ab[:k, k:] @ A22inv_A21, Bb[:k] - Ab[:k, k:] @ A22inv_B2,
                         Cb[:, :k] - Cb[:, k:] @ A22inv_A21, Vb[:, :k])
        Dr = Dr - Cb[:, k:] @ A22inv_B2
    else:
        balanced = Block(Ab[:k, :k], Bb[:k], Cb[:, :k], Vb[:, :k])
    bound = 2.0 * float(np.sum(sigma[k:]))
    if hidden:
        notes.append(f"{len(hidden)} mode(s) that no input reaches or no output sees ({_hz(spec, hidden)}) left out")
    if above:
        notes.append(f"{len(above)} mode(s) above --fmax {fmax:g} Hz ({_hz(spec, above)}) residualised")
    if undamped:
        notes.append(f"{len(undamped)} undamped mode(s) ({_hz(spec, undamped)}) kept as they are (no Gramian without "
                     "damping)")
    info = {"method": "balanced", "match": match, "full_states": int(A.shape[0]), "stable_states": int(part.A.shape[0]),
            "balanced_states": int(k), "rigid_states": int(rigid.A.shape[0]),
            "kept_modes": len(moving_values), "invisible_modes": len(hidden), "residualised_modes": len(above),
            "hankel_singular_values": sigma.tolist(), "error_bound": bound}
    names = mode_state_names(moving_values)
    if len(names) != moving.A.shape[0]:
        names = [f"kept{i + 1}" for i in range(moving.A.shape[0])]
    return _assemble([(rigid, [f"rigid{i + 1}" for i in range(rigid.A.shape[0])]), (moving, names),
                      (balanced, [f"balanced{i + 1}" for i in range(k)])], Dr, info, notes)


def dc_gain(A, B, C, D, rigid_modes: int = 0) -> np.ndarray:
    """D - C A^-1 B over every mode but the rigid ones (split off first, :func:`split`): the
    DC gain of the model without its rigid-body modes."""
    A, B, C, D = (np.asarray(M, dtype=float) for M in (A, B, C, D))
    spec = spectrum(A, B, C, rigid_modes)
    rigid = np.array([k is ModeKind.RIGID for k in spec.kinds])
    _, rest = split(_scaled(A, B, C), spec.values, rigid)
    return D + residual_gain(rest)


def frequency_response(A, B, C, D, freq_hz) -> np.ndarray:
    """G(i 2 pi f) = C (i 2 pi f I - A)^-1 B + D at each frequency (Hz): (frequencies, outputs,
    inputs), complex. A (balanced, :func:`_scaled`) is brought once to complex Schur form
    Z T Z^H (T upper triangular),
    after which each frequency costs one triangular solve (backward stable, O(n^2) per input,
    where a dense solve per frequency is O(n^3))."""
    A, B, C, D = (np.asarray(M, dtype=float) for M in (A, B, C, D))
    scaled = _scaled(A, B, C)  # the same balancing as the reductions: the Schur form is more accurate
    T, Z = scipy.linalg.schur(scaled.A.astype(complex), output="complex")
    Bz, Cz = Z.conj().T @ scaled.B, scaled.C @ Z
    out = np.empty((len(freq_hz), C.shape[0], B.shape[1]), dtype=complex)
    diagonal = np.arange(A.shape[0])
    M = np.empty_like(T)
    for i, f in enumerate(np.asarray(freq_hz, dtype=float)):
        np.negative(T, out=M)
        M[diagonal, diagonal] += 2j * np.pi * f
        out[i] = Cz @ scipy.linalg.solve_triangular(M, Bz, check_finite=False) + D
    return out
