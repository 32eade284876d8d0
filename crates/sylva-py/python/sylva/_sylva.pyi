"""Type stubs of Sylva's Rust module (``sylva._sylva``)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class SylvaError(Exception):
    """Sylva cannot do what was asked; the message says which file, parameter or value, and
    what is allowed."""

class Model:
    """A tree's mesh, its materials and what was made."""

    @property
    def name(self) -> str: ...
    @property
    def summary(self) -> Dict[str, Any]:
        """What was made (for a grown tree: dimensions beside the equations', benefits and
        conflicts under ``street``)."""
    @property
    def triangles(self) -> int: ...
    @property
    def vertices(self) -> int: ...
    @property
    def materials(self) -> Dict[str, List[float]]:
        """Base colours (linear RGBA) of ``bark``, ``leaves`` and ``flowers``."""
    def arrays(self) -> Dict[str, Dict[str, npt.NDArray[Any]]]:
        """Per material with triangles (``bark``, ``leaves``, ``flowers``): ``positions``,
        ``normals`` (n, 3) float32, metres, Z up; ``uvs`` (n, 2) float32; ``indices`` (m, 3)
        uint32; ``shades`` (n,) float32 where the leaves carry light classes."""
    def glb(self) -> bytes:
        """The tree as GLB bytes (glTF 2.0, Y up)."""

def generate(
    species: str,
    seed: int = 0,
    quality: float = 1.0,
    set: Optional[Dict[str, float]] = None,
    levels: Optional[int] = None,
    leaves: bool = True,
    max_triangles: int = 5_000_000,
) -> Model: ...
def grow(
    code: str,
    region: str,
    age: float,
    seed: int = 0,
    season: Optional[str] = None,
    site: Optional[str] = None,
    prices: Optional[str] = None,
    costs: Optional[str] = None,
) -> Model: ...
def rank(
    region: str,
    years: float,
    species: List[str],
    seed: int,
    site: Optional[str],
    prices: Optional[str],
    costs: Optional[str],
    pruning: str,
    by: Optional[str],
) -> List[Dict[str, Any]]: ...
def species() -> List[str]: ...
def street_species() -> List[Dict[str, str]]: ...
def city(settings: str, out: str) -> Dict[str, Any]: ...

class Job:
    """A city's run between its stages, on the process that drives it."""

    def __init__(self, settings: str) -> None: ...
    def growth_tasks(self) -> List[bytes]: ...
    def add_prototypes(self, grown: List[bytes]) -> None: ...
    def lay_out(self) -> int: ...
    def tile_task(self, index: int) -> bytes: ...
    def finish(self, tiles: List[bytes]) -> Tuple[Dict[str, Any], List[Tuple[str, bytes]]]: ...

def run_growth(task: bytes) -> Tuple[bytes, List[Tuple[str, bytes]]]: ...
def run_tile(task: bytes) -> Tuple[bytes, Tuple[str, bytes]]: ...
def stump_file() -> Tuple[str, bytes]: ...
def begin(out: "str | PathLike[str]") -> str: ...
def commit(staging: "str | PathLike[str]", out: "str | PathLike[str]") -> None: ...
def write_files(dir: "str | PathLike[str]", files: List[Tuple[str, bytes]]) -> None: ...
