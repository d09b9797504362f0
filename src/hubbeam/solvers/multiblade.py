"""Multi-blade coordinates of a rotor of N identical, evenly spaced blades (the Coleman
transformation; the definitions of OpenFAST's MBC3, Bir 2008, NREL/CP-500-42553).

**The transformation.** Blade k (k = 0 .. N-1) sits at the azimuth psi_k = psi + 2 pi k / N (rad,
in the sense of the hub's rotation; psi = Omega t + psi_0 on a hub turning at Omega). A quantity q_k
measured on every blade in its own frame (a flap deflection, a twist) is written

    q_k = q_0 + sum_n (q_nc cos(n psi_k) + q_ns sin(n psi_k)) + q_d (-1)^k,  n = 1 .. (N-1)/2,

with the collective q_0 = (1/N) sum_k q_k, the cyclic pairs q_nc = (2/N) sum_k q_k cos(n psi_k),
q_ns = (2/N) sum_k q_k sin(n psi_k), and, for even N, the differential q_d = (1/N) sum_k q_k (-1)^k
(:func:`to_multiblade`). The cyclic pair n = 1 is the tilt of the blades' tip-path plane about two
fixed axes.

**Modes.** A mode of the rotating rotor with frequency omega_r (rad/s) moves blade k as
Re(s_k e^{i omega_r t}). Its blade pattern splits into harmonics p: s_k = sum_p s^p e^{-i p psi_k},
s^p = (1/N) sum_k s_k e^{i p psi_k} (p = 0, +-1, ..., and N/2 for even N;
:func:`harmonic_fractions`): a wave of p nodal diameters travelling round the rotor, forward (in the
sense of rotation) for p > 0. Seen in the non-rotating frame, through the cyclic coordinates of order
|p|, the harmonic p moves at omega_r + p Omega: q_nc + i q_ns = s^p e^{i (omega_r + p Omega) t}
for p = n > 0 (progressive whirl, always forward), and its complex conjugate's
e^{i (n Omega - omega_r) t} for p = -n (regressive: backward while omega_r > n Omega, forward below).
The collective (p = 0) and the differential (p = N/2) keep omega_r (:func:`fixed_frame`). On a
symmetric rotor the harmonics do not couple, so an eigenspace of N blades' equal frequencies
holds one mode of each harmonic (:func:`harmonic_directions` finds them).
"""

from __future__ import annotations

import numpy as np


def harmonic_orders(blades: int) -> list[int]:
    """The harmonics p of N blades in the order the labels use: 0 (collective), 1, -1, 2, -2, ...
    (cyclic pairs: progressive, regressive) and N/2 (differential, N even): N in all."""
    if blades < 1:
        raise ValueError(f"blades: at least 1 (got {blades})")
    out = [0]
    for n in range(1, (blades - 1) // 2 + 1):
        out += [n, -n]
    if blades % 2 == 0 and blades > 1:
        out.append(blades // 2)
    return out


def check_azimuths(azimuths) -> np.ndarray:
    """The azimuths (rad) of N blades in their order, checked to be evenly spaced
    (psi_k = psi_0 + 2 pi k / N to 1e-9 rad, in the sense of rotation); ValueError otherwise."""
    psi = np.asarray(azimuths, dtype=float)
    n = psi.size
    steps = np.mod(np.diff(psi) - 2.0 * np.pi / n + np.pi, 2.0 * np.pi) - np.pi
    if n < 1 or np.any(np.abs(steps) > 1e-9):
        raise ValueError(f"azimuths: {n} blades are not evenly spaced in their order "
                         f"(expected steps of {360.0 / max(n, 1):g} deg, got {np.degrees(np.diff(psi)).round(6).tolist()})")
    return psi


def to_multiblade(blade_values, azimuths) -> np.ndarray:
    """The multi-blade coordinates [q_0, q_1c, q_1s, q_2c, q_2s, ..., q_d] (last axis, N
    entries) of blade values q_k (last axis over the N blades) at the blade azimuths psi_k (rad;
    the same shape, or (N,) for every row): the MBC3 transformation of the module doc."""
    q = np.asarray(blade_values)
    psi = np.broadcast_to(np.asarray(azimuths, dtype=float), q.shape)
    n = q.shape[-1]
    out = [q.mean(axis=-1)]
    for order in range(1, (n - 1) // 2 + 1):
        out += [2.0 / n * np.sum(q * np.cos(order * psi), axis=-1), 2.0 / n * np.sum(q * np.sin(order * psi), axis=-1)]
    if n % 2 == 0 and n > 1:
        out.append(np.mean(q * (-1.0) ** np.arange(n), axis=-1))
    return np.stack(out, axis=-1)


def harmonic_fractions(blade_vectors, azimuths) -> dict[int, float]:
    """The share (summing to 1) of each harmonic p (:func:`harmonic_orders`) in a mode's blade
    pattern: blade_vectors (N, m), blade k's motion (any m numbers measured alike on every
    blade, complex for a complex mode), N |s^p|^2 / sum_k |s_k|^2 (Parseval)."""
    s = np.asarray(blade_vectors)
    psi = np.asarray(azimuths, dtype=float)
    total = float(np.sum(np.abs(s) ** 2))
    if not total > 0.0:
        raise ValueError("a mode that does not move the blades has no harmonic content")
    n = psi.size
    return {p: float(n * np.sum(np.abs(np.exp(1j * p * psi) @ s / n) ** 2) / total) for p in harmonic_orders(n)}


def harmonic_directions(blade_vectors, azimuths) -> list[tuple[int, np.ndarray, float]]:
    """The pure harmonics inside an eigenspace: ``blade_vectors`` (modes k, N, m) are the blade
    patterns of k modes of one (repeated) frequency. Returns (p, c, purity) for each direction c
    (k coefficients: the mode sum_i c_i mode_i) whose pattern is the harmonic p, purity its
    share of harmonic p (1 on a symmetric rotor); in the order of :func:`harmonic_orders`, then
    by purity. Directions whose pattern is no single harmonic (below one half) are not returned:
    the caller sees fewer directions than modes.

    With s^p_i = (1/N) sum_k s_ik e^{i p psi_k} the harmonic p of mode i, the share of harmonic
    p in the mode sum_i c_i mode_i is c^H G_p c / c^H G c, G_p = N S^p (S^p)^H and G = sum_p G_p
    the Gram matrix of the patterns (Parseval): the directions are the eigenvectors of G_p
    relative to G with eigenvalues near 1 (here the singular vectors of sqrt(N) W^H S^p, W
    whitening G)."""
    s = np.asarray(blade_vectors)
    k, n, m = s.shape
    psi = check_azimuths(azimuths)
    orders = harmonic_orders(n)
    transform = np.exp(1j * np.outer(orders, psi)) / n  # (harmonics, N)
    parts = np.sqrt(n) * np.einsum("pk,ikm->pim", transform, s)  # sqrt(N) s^p_i
    gram = np.einsum("pim,pjm->ij", np.conj(parts), parts)
    mu, W = np.linalg.eigh(0.5 * (gram + np.conj(gram).T))
    keep = mu > max(mu[-1], 0.0) * 1e-14 if mu.size else np.zeros(0, bool)
    whiten = W[:, keep] / np.sqrt(mu[keep])
    out = []
    for p, part in zip(orders, parts):  # c = W d: c^H G_p c = |A d|^2, A = (S^p)^T W
        _, sigma, vh = np.linalg.svd(part.T @ whiten, full_matrices=False)
        for j in np.flatnonzero(sigma**2 > 0.5):
            out.append((p, whiten @ np.conj(vh[j]), float(sigma[j] ** 2)))
    return out


def cyclic_order(p: int, blades: int) -> int:
    """The order n of the multi-blade coordinates that carry harmonic p: 0 collective, N/2
    differential, |p| cyclic."""
    return abs(p) if 2 * abs(p) != blades else blades // 2


def fixed_frame(frequency_hz, p: int, blades: int, omega: float):
    """(frequency (Hz) seen in the non-rotating frame, whirl) of harmonic p of a mode at
    ``frequency_hz`` in the rotating frame, on a hub at omega (rad/s): omega_r + p Omega for a
    cyclic harmonic (|.|), the same frequency for the collective and the differential. Whirl:
    "forward" or "backward" (the sense of the cyclic coordinates' motion against the rotation),
    "" for the collective and the differential."""
    f = np.asarray(frequency_hz, dtype=float)
    if p == 0 or 2 * p == blades:
        return f, np.full(f.shape, "", dtype=object)
    signed = np.sign(p) * (f + p * omega / (2.0 * np.pi))
    return np.abs(f + p * omega / (2.0 * np.pi)), np.where(signed >= 0.0, "forward", "backward").astype(object)


def harmonic_label(p: int, blades: int, frame: str) -> str:
    """The multi-blade name of harmonic p: "collective", "differential"; in the rotating frame
    "cyclic" (n = 1) or "cyclic-n", in the fixed frame "progressive" (p > 0) or "regressive"
    (p < 0), with " cyclic-n" for n >= 2."""
    if p == 0:
        return "collective"
    if 2 * p == blades:
        return "differential"
    n = abs(p)
    higher = f"cyclic-{n}" if n > 1 else ""
    if frame == "rotating":
        return higher or "cyclic"
    sense = "progressive" if p > 0 else "regressive"
    return f"{sense} {higher}".strip()
