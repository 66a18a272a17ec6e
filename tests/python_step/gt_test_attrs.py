"""Python attributes for tests/python_step: one that equals a built-in, and ones that go wrong."""

import numpy as np

WINDOW = 9  # the built-in rms's default window; halo [0, 0, 4]
HALF = WINDOW // 2


def _rms_interior(block):
    # The built-in's operations in its order (plugins/attributes: squares, then the centre plus
    # the pairs of taps t = 1..4 each side, times 1/9 in float), so the values are the same bits.
    squares = block * block
    n = block.shape[2] - 2 * HALF
    total = squares[:, :, HALF:HALF + n].copy()
    for t in range(1, HALF + 1):
        total += squares[:, :, HALF + t:HALF + t + n] + squares[:, :, HALF - t:HALF - t + n]
    return np.sqrt(total * (np.float32(1) / np.float32(WINDOW)))


def rms(block):
    """RMS over 9 samples along the trace; returns the block without its halo."""
    return _rms_interior(block)


def rms_whole(block):
    """The same, returned in the shape it was given (the step crops the halo)."""
    out = np.zeros_like(block)
    out[:, :, HALF:block.shape[2] - HALF] = _rms_interior(block)
    return out


import os

_calls = 0


def fails_later(block):
    """RMS for the first blocks, then a ValueError: components of the first blocks get committed."""
    global _calls
    _calls += 1
    if _calls > int(os.environ.get("GT_TEST_FAIL_AFTER", "6")):
        raise ValueError("no attribute past call %d (block of shape %s)" % (_calls - 1, block.shape))
    return _rms_interior(block)


def float64(block):
    return block.astype(np.float64)


def wrong_shape(block):
    return block[:, :, 1:]


def not_an_array(block):
    return float(block.mean())


def nan_here(block):
    out = block.copy()
    out[tuple(n // 2 for n in out.shape)] = np.nan  # inside the block, not in its halo
    return out


not_callable = 42
