"""Exceptions raised by geotandem.

Every error of the C++ libraries arrives as one of these, with the message the command line prints
(``str(e)``: where, what, and what to do) and its parts as attributes. Interrupting a long call
(Ctrl-C, or the notebook's stop button) raises the built-in :class:`KeyboardInterrupt` once the
work has stopped; what it committed to a store stays there.
"""

from __future__ import annotations

from typing import Optional

__all__ = ["Error", "InvalidArgumentError", "RecipeError", "IoError", "FormatError", "DataError"]


class Error(Exception):
    """Base of geotandem's errors.

    Attributes: ``message`` (without the place and hint), ``file``, ``line``, ``column`` (1-based,
    ``None`` when they do not apply), ``hint`` (what to do) and ``exit_code`` (the command line's
    exit status for this error: 2 bad argument, 3 cannot read/write, 4 damaged file, 5 data refused).
    """

    def __init__(self, text: str, *, message: Optional[str] = None, file: Optional[str] = None,
                 line: Optional[int] = None, column: Optional[int] = None, hint: Optional[str] = None,
                 exit_code: int = 1) -> None:
        super().__init__(text)
        self.message = message if message is not None else text
        self.file = file
        self.line = line
        self.column = column
        self.hint = hint
        self.exit_code = exit_code


class InvalidArgumentError(Error, ValueError):
    """A bad argument or parameter: a value out of range, an unknown key, a box outside the cube."""


class RecipeError(InvalidArgumentError):
    """A recipe (or another text file the user wrote) is invalid; ``file``, ``line`` and ``column``
    say where."""


class IoError(Error, OSError):
    """A file could not be opened, read or written."""


class FormatError(Error):
    """A file was read but is not what it should be: unknown format, truncated, a damaged record of
    a store (the message names the component's key, shard and offset, as ``geotandem store check``
    does)."""


class DataError(Error):
    """The data holds something the operation refuses (NaN samples under ``nan="error"``)."""
