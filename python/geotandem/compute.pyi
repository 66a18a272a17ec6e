# Type hints of geotandem.compute: extract()'s parameters are built at import time from the C++
# declarations; they are spelled out here for checkers and editors.
import os
from typing import Any, Callable, Dict, Mapping, Optional, Sequence, Union

from .store import Store

PathLike = Union[str, os.PathLike[str]]
ProgressArg = Union[None, bool, str, Callable[..., Any]]

def extract_parameters() -> Dict[str, Dict[str, Any]]: ...
def geometry_of(volume: Any = ..., *, shape: Optional[Sequence[int]] = ..., spacing: Optional[Sequence[float]] = ...,
                origin: Optional[Sequence[float]] = ..., z_unit: Optional[str] = ...,
                inline0: Optional[float] = ..., crossline0: Optional[float] = ...,
                geometry: Optional[Mapping[str, Any]] = ...) -> Dict[str, Any]: ...
def extract(volume: Any, iso: float, *, out: PathLike, workers: Optional[int] = ..., fresh: bool = ...,
            nan: str = ..., no_data: Optional[float] = ..., spacing: Optional[Sequence[float]] = ...,
            origin: Optional[Sequence[float]] = ..., z_unit: Optional[str] = ...,
            geometry: Optional[Mapping[str, Any]] = ..., crs: Any = ..., progress: ProgressArg = ...,
            side: str = ..., max_error: float = ..., isotropy: float = ..., axis: str = ..., block_size: int = ...,
            mode: str = ..., extended_time_lag: bool = ...) -> Store: ...
def run_workflow(recipe: PathLike, overrides: Optional[Mapping[str, Any]] = ..., *, fresh: bool = ...,
                 dry_run: bool = ..., progress: ProgressArg = ...) -> Dict[str, Any]: ...
def synth(out: PathLike, *, kind: str = ..., shape: Sequence[int] = ..., seed: int = ..., overwrite: bool = ...,
          progress: ProgressArg = ...) -> str: ...
