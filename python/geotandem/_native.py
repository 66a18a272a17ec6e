"""Where the compiled part and its companions are: geotandem._core, the ``geotandem`` executable
(worker processes run it) and the plugin directory. An installed package carries them under
geotandem/_native; a package imported from a build tree (tests) finds them through _build_paths."""

from __future__ import annotations

import os
from pathlib import Path
from typing import List

from . import _core  # noqa: F401  (re-exported for the other modules)

_here = Path(__file__).resolve().parent


def executable() -> str:
    """The ``geotandem`` executable the worker processes run ($GEOTANDEM_EXECUTABLE first)."""
    env = os.environ.get("GEOTANDEM_EXECUTABLE")
    if env:
        return env
    installed = _here / "_native" / "bin" / "geotandem"
    if installed.exists():
        return str(installed)
    try:
        from . import _build_paths  # type: ignore[attr-defined]
        return str(_build_paths.executable)
    except ImportError:
        return "geotandem"


def worker_command() -> List[str]:
    return [executable(), "worker"]


def plugin_path() -> str:
    """$GEOTANDEM_PLUGIN_PATH, then the plugins installed with the package or built beside it."""
    parts = [p for p in os.environ.get("GEOTANDEM_PLUGIN_PATH", "").split(":") if p]
    installed = _here / "_native" / "lib" / "geotandem" / "plugins"
    if installed.exists():
        parts.append(str(installed))
    else:
        try:
            from . import _build_paths  # type: ignore[attr-defined]
            parts.append(str(_build_paths.plugin_dir))
        except ImportError:
            pass
    return ":".join(parts)
