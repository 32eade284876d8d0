from os import PathLike
from typing import Any, Iterable, Mapping, Optional, Sequence, Union

from ._sylva import Model as Model, SylvaError as SylvaError, __version__ as __version__
from ._sylva import species as species, street_species as street_species

_Path = Union[str, "PathLike[str]"]

def generate(
    species: str,
    *,
    seed: int = 0,
    quality: float = 1.0,
    set: Optional[Mapping[str, float]] = None,
    levels: Optional[int] = None,
    leaves: bool = True,
    max_triangles: int = 5_000_000,
) -> Model: ...
def grow(
    code: str,
    *,
    region: str,
    age: float,
    seed: int = 0,
    season: Optional[str] = None,
    site: Optional[_Path] = None,
    prices: Optional[_Path] = None,
    costs: Optional[_Path] = None,
) -> Model: ...
def city_settings(
    inventory: _Path,
    *,
    layer: Optional[str] = None,
    columns: Optional[Mapping[str, Union[str, Sequence[str]]]] = None,
    dbh_unit: Optional[str] = None,
    circumference_unit: Optional[str] = None,
    height_unit: Optional[str] = None,
    crs: Optional[Union[str, int]] = None,
    region: Optional[str] = None,
    variants: int = 2,
    stumps: bool = False,
    years: Iterable[int] = (0,),
    year: int = 2026,
    ground: float = 0.0,
    seed: int = 0,
) -> str: ...
def city(inventory: Any, out: _Path, **options: Any) -> dict: ...

class inventory_file:
    def __init__(self, inventory: Any, options: Mapping[str, Any]) -> None: ...
    def __enter__(self) -> tuple: ...
    def __exit__(self, *exc: Any) -> bool: ...
