"""Seismic attributes written in numpy, for the recipe step `python` (docs/plugins.md).

Each function takes one block of the cube plus its halo, a float32 array of shape
(inlines, crosslines, samples) with the trace along the last axis, and returns the attribute of the
block: a float32 array of the shape it was given (geotandem crops the halo) or of that shape less
the halo. Near the cube's faces the halo holds the cube mirrored about the face, as for the
built-in attributes, so a function never sees a short block.

    - step: python
      as: envelope
      input: input
      function: seismic_attrs:envelope
      halo: [0, 0, 32]      # samples each side: inline, crossline, sample
      path: ../examples/python_attribute   # this directory, relative to the recipe
"""

import numpy as np


HALF_LENGTH = 32  # samples: the envelope's halo along the trace is [0, 0, HALF_LENGTH]


def _hilbert_taps(half_length):
    """Taps w(t), t = 1 .. half_length, of a windowed Hilbert transformer: 2 / (pi t) for odd t, 0 for
    even t, tapered by a Blackman window that reaches 0 at t = half_length + 1."""
    t = np.arange(1, half_length + 1)
    x = t / (half_length + 1)
    window = 0.42 + 0.5 * np.cos(np.pi * x) + 0.08 * np.cos(2 * np.pi * x)
    return np.where(t % 2 == 1, 2.0 / (np.pi * t) * window, 0.0).astype(np.float32)


_TAPS = _hilbert_taps(HALF_LENGTH)


def envelope(block):
    """Instantaneous amplitude |u + i H[u]|, with H a 65-tap Hilbert transformer along the trace.

    Box independence: every output sample is the same sum of the same products in the same order,
    whatever block it is computed in, so two blocks agree bit for bit where they meet (the
    extraction stitches blocks by their samples and refuses blocks that disagree). An FFT over the
    block would not: its result depends on the block's length.
    """
    h = HALF_LENGTH
    n = block.shape[2] - 2 * h
    u = block[:, :, h:h + n]
    quadrature = np.zeros(u.shape, np.float32)
    scratch = np.empty(u.shape, np.float32)
    for t in range(1, h + 1, 2):  # the even taps are 0
        np.subtract(block[:, :, h - t:h - t + n], block[:, :, h + t:h + t + n], out=scratch)
        scratch *= _TAPS[t - 1]
        quadrature += scratch
    np.multiply(quadrature, quadrature, out=quadrature)
    np.multiply(u, u, out=scratch)
    scratch += quadrature
    return np.sqrt(scratch, out=scratch)  # the block less its halo


def rms(block, window=9):
    """RMS amplitude over `window` samples along the trace (odd; halo [0, 0, window // 2]).

    The window's sum is added tap by tap in a fixed order (a running cumulative sum would round
    differently in each block, and blocks must agree bit for bit).
    """
    half = window // 2
    n = block.shape[2] - 2 * half
    squares = block * block
    total = squares[:, :, 0:n].copy()
    for t in range(1, window):
        total += squares[:, :, t:t + n]
    total *= np.float32(1) / np.float32(window)
    return np.sqrt(total, out=total)  # the block less its halo
