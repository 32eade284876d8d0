"""Sylva from Python: realistic trees as numpy arrays and GLB, street trees grown from the
USDA Urban Tree Database with their benefits and conflicts, and cities tiled as 3D Tiles.

    >>> import sylva
    >>> tree = sylva.generate("quaking_aspen", seed=1)
    >>> tree.arrays()["bark"]["positions"].shape      # (n, 3) float32, metres, Z up
    >>> oak = sylva.grow("QURU", region="NoEast", age=30)
    >>> oak.summary["height_m"], oak.summary["height_measured_m"]

The heavy work is Rust (``sylva._sylva``); every long call lets go of the GIL. Errors are
``sylva.SylvaError`` with Sylva's message.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Iterable, Mapping, Optional, Sequence, Union

from . import _sylva
from ._sylva import Model, SylvaError, __version__, species, street_species

__all__ = [
    "Model",
    "SylvaError",
    "__version__",
    "city",
    "city_settings",
    "generate",
    "grow",
    "rank",
    "species",
    "street_species",
]

PathLike = Union[str, "os.PathLike[str]"]


def generate(
    species: str,
    *,
    seed: int = 0,
    quality: float = 1.0,
    set: Optional[Mapping[str, float]] = None,
    levels: Optional[int] = None,
    leaves: bool = True,
    max_triangles: int = 5_000_000,
) -> Model:
    """A Weber & Penn (1995) tree.

    ``species`` is a built-in name (``sylva.species()``), a Sylva ``.toml`` or an Arbaro
    ``.xml`` file; ``set`` overrides parameters by name, e.g. ``{"1Branches": 30}``;
    ``quality`` scales the mesh's resolution; ``levels`` stops the branching early.
    """
    overrides = {str(k): float(v) for k, v in (set or {}).items()}
    return _sylva.generate(
        str(species), seed, float(quality), overrides, levels, bool(leaves), int(max_triangles)
    )


def grow(
    code: str,
    *,
    region: str,
    age: float,
    seed: int = 0,
    season: Optional[str] = None,
    site: Optional[PathLike] = None,
    prices: Optional[PathLike] = None,
    costs: Optional[PathLike] = None,
) -> Model:
    """A street tree grown year by year to ``age`` by ``region``'s equations of the USDA
    Urban Tree Database (McPherson et al. 2016).

    ``code`` is a species code (``QURU``) or its scientific or common name. The model's
    ``summary`` holds the grown tree's dimensions beside the equations' (``height_m`` and
    ``height_measured_m``, ...), and under ``street`` the year's benefits (CO2, rain, energy,
    dollars), costs and conflicts with the ``site`` (a TOML file as ``sylva grow --site``
    reads it: wires, façade, lamp posts).
    """
    return _sylva.grow(
        str(code),
        str(region),
        float(age),
        seed,
        season,
        _path(site),
        _path(prices),
        _path(costs),
    )


def rank(
    region: str,
    *,
    years: float = 40,
    species: Optional[Iterable[str]] = None,
    seed: int = 0,
    site: Optional[PathLike] = None,
    prices: Optional[PathLike] = None,
    costs: Optional[PathLike] = None,
    pruning: str = "regime",
    by: Optional[str] = None,
) -> list:
    """``region``'s species grown yearly for ``years`` and ranked by net benefit per tree
    planted, best first, as ``sylva rank --json`` writes them: one dict per species
    (``net_usd``, ``benefits_usd``, ``costs_usd``, ``typical`` and ``site`` sums by i-Tree's
    categories, ``costs_by_item_usd`` and ``costs_by_payer_usd`` (city, utility, owners),
    ``conflict_costs``, ``conflict_years``, ``does_not_suit``, ``first_conflicts``,
    ``pruning``, ``not_computed``).

    ``species`` limits the ranking to those codes; ``site``, ``prices`` and ``costs`` are TOML
    files as ``sylva rank`` reads them; ``pruning`` is ``"regime"`` (the site's cycles cut
    the tree), ``"compare"`` (also the benefits each year's cuts cost) or ``"off"``; ``by`` is
    ``"typical"`` or ``"site"`` (default: the site's net where a site is given).
    """
    return _sylva.rank(
        str(region),
        float(years),
        [str(c) for c in (species or [])],
        int(seed),
        _path(site),
        _path(prices),
        _path(costs),
        str(pruning),
        by,
    )


def city_settings(
    inventory: PathLike,
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
) -> str:
    """A city's settings as the Rust side reads them (JSON); see :func:`city`."""
    cols: dict = {}
    for key, value in (columns or {}).items():
        if isinstance(value, str):
            cols[str(key)] = value
        elif isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            cols[str(key)] = list(value)
        else:
            raise SylvaError(
                f"columns: `{key}` is {value!r}; expected a column name or a list of names"
            )
    return json.dumps(
        {
            "inventory": os.fspath(inventory),
            "layer": layer,
            "columns": cols,
            "dbh_unit": dbh_unit,
            "circumference_unit": circumference_unit,
            "height_unit": height_unit,
            "crs": None if crs is None else str(crs),
            "region": region,
            "variants": int(variants),
            "stumps": bool(stumps),
            "years": [int(y) for y in years],
            "year": int(year),
            "ground": float(ground),
            "seed": int(seed),
        }
    )


def city(inventory: Any, out: PathLike, **options: Any) -> dict:
    """Tiles a city's street-tree inventory as OGC 3D Tiles in ``out`` (one tileset per epoch,
    the grown trees shared) on this machine's threads, as ``sylva city`` does; its summary.

    ``inventory`` is a CSV, GeoJSON or GeoPackage file, a pandas DataFrame (columns as in a
    CSV), or a geopandas GeoDataFrame of points (its geometry and CRS are used). Options, as
    ``sylva city``'s flags: ``layer``, ``columns`` (``{"species": ["latin", "common"],
    "dbh": "diameter", "x": "POINT_X", "y": "POINT_Y", ...}``), ``dbh_unit``,
    ``circumference_unit``, ``height_unit``, ``crs`` (``"EPSG:2263"``), ``region``,
    ``variants``, ``stumps``, ``years`` (``[0, 10, 25]``), ``year``, ``ground``, ``seed``.
    """
    with inventory_file(inventory, options) as (path, options):
        return _sylva.city(city_settings(path, **options), os.fspath(out))


class inventory_file:
    """A context giving a file path for ``inventory`` (a path, or a frame written to a
    temporary CSV) and the options to read it with."""

    def __init__(self, inventory: Any, options: Mapping[str, Any]):
        self._inventory = inventory
        self._options = dict(options)
        self._dir: Optional[tempfile.TemporaryDirectory] = None

    def __enter__(self):
        inv = self._inventory
        if isinstance(inv, (str, os.PathLike)):
            return os.fspath(inv), self._options
        from . import frames

        self._dir = tempfile.TemporaryDirectory(prefix="sylva-inventory-")
        path = os.path.join(self._dir.name, "inventory.csv")
        options = frames.write_csv(inv, path, self._options)
        return path, options

    def __exit__(self, *exc):
        if self._dir is not None:
            self._dir.cleanup()
        return False


def _path(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)
