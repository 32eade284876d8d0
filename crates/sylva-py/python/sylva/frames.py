"""pandas and geopandas inventories: written to a CSV that ``sylva city`` reads, the
geometry of a GeoDataFrame's points as projected x and y (or longitude and latitude) columns
and its CRS as the EPSG code."""

from __future__ import annotations

from typing import Any, Dict, Mapping


def write_csv(frame: Any, path: str, options: Mapping[str, Any]) -> Dict[str, Any]:
    """Writes ``frame`` to ``path`` as CSV; the options to read it with."""
    options = dict(options)
    to_csv = getattr(frame, "to_csv", None)
    if to_csv is None:
        raise TypeError(
            f"inventory: expected a file path or a pandas/geopandas frame, not {type(frame).__name__}"
        )
    geometry = getattr(frame, "geometry", None) if hasattr(frame, "crs") else None
    if geometry is not None:
        frame = _with_coordinates(frame, options)
    frame.to_csv(path, index=False)
    return options


def _with_coordinates(gdf: Any, options: Dict[str, Any]) -> Any:
    from ._sylva import SylvaError

    kinds = set(gdf.geometry.geom_type.dropna().unique())
    if kinds - {"Point"}:
        raise SylvaError(
            f"inventory: a GeoDataFrame of points is needed; it holds {', '.join(sorted(kinds))}"
        )
    frame = gdf.drop(columns=[gdf.geometry.name])
    crs = gdf.crs
    columns = dict(options.get("columns") or {})
    epsg = crs.to_epsg() if crs is not None else None
    if crs is not None and crs.is_geographic:
        frame["sylva_lon"], frame["sylva_lat"] = gdf.geometry.x, gdf.geometry.y
        columns.update({"lon": "sylva_lon", "lat": "sylva_lat"})
    else:
        if epsg is None:
            raise SylvaError(
                "inventory: the GeoDataFrame's coordinate system has no EPSG code; "
                "set one with gdf.set_crs(...) or gdf.to_crs(...)"
            )
        frame["sylva_x"], frame["sylva_y"] = gdf.geometry.x, gdf.geometry.y
        columns.update({"x": "sylva_x", "y": "sylva_y"})
        options["crs"] = f"EPSG:{epsg}"
    options["columns"] = columns
    return frame
