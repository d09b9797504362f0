"""Dominant frequency of a sampled signal (the paper's "FFT analysis", Sec. 5).

Steps: remove the mean (and, optionally, a linear trend), apply a window (Hann by
default), zero-pad to ``padding`` times the length, take the one-sided amplitude
spectrum, pick the largest peak above ``min_hz`` and refine it by fitting a parabola
to the logarithm of the three bins around it (exact for a Gaussian peak, and within a
small fraction of a bin for the Hann window's main lobe).

Resolution: the record of duration T separates two frequencies only if they are more
than about 1/T apart (for the Hann window, 2/T between the first zeros of the main
lobe); zero padding and interpolation do not change that, they only locate the peak of
one isolated component more finely. :class:`FrequencyEstimate` reports both numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import detrend, get_window


@dataclass(frozen=True)
class FrequencyEstimate:
    """frequency_hz: the interpolated peak; resolution_hz: 1/T, the spacing of independent
    spectral lines (two components closer than this are not separated); bin_hz: the
    padded grid; amplitude: the windowed spectrum's peak, normalised so that a pure
    sinusoid of amplitude a gives about a."""

    frequency_hz: float
    resolution_hz: float
    bin_hz: float
    amplitude: float


def dominant_frequency(t, y, window: str = "hann", padding: int = 16, min_hz: float | None = None,
                       trend: str = "constant") -> FrequencyEstimate:
    """The strongest spectral peak of y(t) (uniform sampling required), see the module doc.

    ``min_hz`` (default 1.5 / T) skips the lowest lines, where a slow drift or a
    non-zero final value leaves energy; ``trend``: 'constant' (remove the mean) or
    'linear' (remove a straight line).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.ndim != 1 or t.shape != y.shape or t.size < 8:
        raise ValueError("need at least 8 samples of y(t), as two 1-D arrays of one length")
    dt = np.diff(t)
    if np.any(dt <= 0) or np.ptp(dt) > 1e-6 * dt.mean():
        raise ValueError("samples must be uniformly spaced in time")
    dt = dt.mean()
    n = y.size
    duration = n * dt
    w = get_window(window, n)
    yw = detrend(y, type=trend) * w
    nfft = int(2 ** np.ceil(np.log2(n * padding)))
    spectrum = np.abs(np.fft.rfft(yw, nfft)) * 2.0 / w.sum()
    freqs = np.fft.rfftfreq(nfft, dt)
    lo = 1.5 / duration if min_hz is None else min_hz
    valid = np.flatnonzero(freqs >= lo)
    if valid.size < 3:
        raise ValueError(f"no spectral lines above {lo:g} Hz: the record is too short")
    k = valid[np.argmax(spectrum[valid])]
    k = min(max(k, 1), spectrum.size - 2)
    a, b, c = np.log(np.maximum(spectrum[k - 1 : k + 2], 1e-300))
    denom = a - 2 * b + c
    shift = 0.5 * (a - c) / denom if denom < 0 else 0.0
    df = freqs[1] - freqs[0]
    return FrequencyEstimate(float(freqs[k] + shift * df), 1.0 / duration, float(df),
                             float(np.exp(b - 0.25 * (a - c) * shift)))
