"""How long calls show their progress.

``progress=None`` (the default) picks: in a Jupyter kernel one line per task that updates itself
(and the log lines), elsewhere the command line's own lines on stderr (a bar on a terminal).
``progress=False`` shows nothing but warnings; ``progress="terminal"`` or ``"notebook"`` force one.
A callable ``f(label, done, total, unit, seconds, state)`` receives every update instead.
"""

from __future__ import annotations

import sys
from typing import Any, Callable, Optional, Tuple, Union

ProgressArg = Union[None, bool, str, Callable[..., Any]]


def _in_notebook() -> bool:
    shell = sys.modules.get("IPython")
    if shell is None:
        return False
    try:
        ip = shell.get_ipython()  # type: ignore[attr-defined]
    except Exception:
        return False
    return ip is not None and "IPKernelApp" in getattr(ip, "config", {})


class _NotebookLine:
    """One line per task, redrawn with a carriage return (Jupyter's stream output honours it)."""

    def __init__(self, stream: Any = None, user: Optional[Callable[..., Any]] = None) -> None:
        self.stream = stream
        self.user = user

    def __call__(self, kind: str, *payload: Any) -> None:
        out = self.stream or sys.stderr
        if kind == "log":
            out.write(payload[0])
            out.flush()
            return
        label, done, total, unit, seconds, state = payload
        if self.user is not None:
            self.user(label, done, total, unit, seconds, state)
            return
        if total:
            text = f"{label}: {100.0 * done / total:5.1f} % ({done}/{total} {unit}) {seconds:.1f} s"
        else:
            text = f"{label}: {done} {unit} {seconds:.1f} s"
        if state == "done":
            text += " done"
        elif state == "stopped":
            text += " stopped"
        out.write("\r" + text + ("\n" if state != "running" else ""))
        out.flush()


def resolve(progress: ProgressArg) -> Tuple[str, Any]:
    """(mode, sink) for the compiled calls: mode "terminal", "callback" or "quiet"."""
    if progress is False:
        return "quiet", _NotebookLine()  # warnings still reach stderr
    if callable(progress):
        return "callback", _NotebookLine(user=progress)
    if progress == "terminal" or (progress in (None, True) and not _in_notebook()):
        return "terminal", None
    if progress in (None, True, "notebook"):
        return "callback", _NotebookLine()
    raise ValueError(f"progress={progress!r}: use None, False, 'terminal', 'notebook' or a callable")
