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


def envelope(block):
    """Instantaneous amplitude |u + i H[u]|, with the Hilbert transform H computed by FFT along the trace.

    An FFT treats the trace as periodic: with a halo of about 32 samples each side (mirrored at the
    cube's top and bottom) the wrap-around stays in the halo, which geotandem crops.
    """
    spectrum = np.fft.rfft(block, axis=2)
    # H multiplies positive frequencies by -i; the mean (and the Nyquist term of an even length) by 0.
    spectrum *= -1j
    spectrum[:, :, 0] = 0
    if block.shape[2] % 2 == 0:
        spectrum[:, :, -1] = 0
    quadrature = np.fft.irfft(spectrum, n=block.shape[2], axis=2).astype(np.float32)
    return np.sqrt(block * block + quadrature * quadrature)


def rms(block, window=9):
    """RMS amplitude over `window` samples along the trace (halo [0, 0, window // 2])."""
    half = window // 2
    squares = np.square(block, dtype=np.float32)
    sums = np.cumsum(squares, axis=2, dtype=np.float64)
    sums = np.concatenate([np.zeros(block.shape[:2] + (1,)), sums], axis=2)
    inner = (sums[:, :, window:] - sums[:, :, :-window]) / window
    return np.sqrt(np.maximum(inner, 0.0)).astype(np.float32)  # the block less its halo
