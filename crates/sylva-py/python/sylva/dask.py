"""A city tiled across a Dask cluster, with the same bytes as ``sylva city`` on one machine.

A city's run is a chain of pure tasks (``sylva_city::tasks`` in the Rust crate):

1. the driver reads and plans the inventory (``Job``: cheap, one process);
2. growth tasks, one per species, region and seed variant, grow the trees the city shares;
3. the driver lays each epoch out in a quadtree of tiles;
4. tile tasks, one per tile and epoch, each carrying the trees and grown trees it draws, make
   the tiles' GLB files;
5. the driver writes each epoch's ``tileset.json`` and ``summary.json``.

Tasks travel as bytes, so workers need nothing but ``sylva`` installed. By default the files
come back to the driver, which writes them (no shared filesystem needed); with
``write="workers"`` each worker writes its own files straight into the output folder, which
must then be on a filesystem every worker sees (NFS, a cluster's shared disk).

    >>> from distributed import Client, LocalCluster
    >>> import sylva.dask
    >>> with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
    ...     summary = sylva.dask.city("trees.csv", "tiles", client=client, years=[0, 10])
"""

from __future__ import annotations

import os
import shutil
import time
from typing import Any, Dict, List, Optional, Tuple

from . import _sylva, city_settings, inventory_file

__all__ = ["city", "estimate"]


def _grow(task: bytes, staging: Optional[str]) -> Tuple[bytes, list, float]:
    t0 = time.perf_counter()
    prototypes, files = _sylva.run_growth(task)
    if staging is not None:
        _sylva.write_files(staging, files)
        files = [(path, len(data)) for path, data in files]
    return prototypes, files, time.perf_counter() - t0


def _tile(task: bytes, staging: Optional[str]) -> Tuple[bytes, tuple, float]:
    t0 = time.perf_counter()
    tile, (path, glb) = _sylva.run_tile(task)
    if staging is not None:
        _sylva.write_files(staging, [(path, glb)])
        glb = len(glb)
    return tile, (path, glb), time.perf_counter() - t0


def city(
    inventory: Any,
    out: "os.PathLike[str] | str",
    *,
    client: Any = None,
    write: str = "driver",
    in_flight: int = 256,
    retries: int = 2,
    **options: Any,
) -> Dict[str, Any]:
    """Tiles a city as :func:`sylva.city` does, its growth and tile tasks run on the Dask
    cluster of ``client`` (the current client if none). The files are byte for byte those of
    ``sylva city`` with the same options.

    ``write``: ``"driver"`` (files come back and this process writes them) or ``"workers"``
    (each worker writes its own into ``out``'s staging folder on a shared filesystem).
    ``in_flight`` bounds the tile tasks submitted at once, so the driver's memory stays
    bounded however large the city. Returns the summary (``summary.json``'s contents) with
    ``"task_seconds"``: each growth and tile task's seconds on its worker, for
    :func:`estimate`.
    """
    from distributed import as_completed, get_client

    if write not in ("driver", "workers"):
        raise ValueError(f"write={write!r}: expected 'driver' or 'workers'")
    client = client or get_client()
    t0 = time.perf_counter()
    with inventory_file(inventory, options) as (path, opts):
        job = _sylva.Job(city_settings(path, **opts))
    planned = time.perf_counter() - t0
    staging = os.fspath(_sylva.begin(os.fspath(out)))
    on_workers = staging if write == "workers" else None
    seconds: Dict[str, List[float]] = {"growth": [], "tiles": []}
    try:
        tasks = job.growth_tasks()
        futures = client.map(_grow, tasks, [on_workers] * len(tasks), pure=False, retries=retries)
        grown = []
        for _, (prototypes, files, s) in as_completed(futures, with_results=True):
            if on_workers is None:
                _sylva.write_files(staging, files)
            grown.append(prototypes)
            seconds["growth"].append(s)
        job.add_prototypes(grown)
        _sylva.write_files(staging, [_sylva.stump_file()])
        grown_at = time.perf_counter()
        count = job.lay_out()
        tiles = []
        pending = as_completed([], with_results=True)
        submitted = 0

        def submit(k: int) -> None:
            nonlocal submitted
            for i in range(submitted, min(count, submitted + k)):
                pending.add(client.submit(_tile, job.tile_task(i), on_workers, pure=False, retries=retries))
            submitted = min(count, submitted + k)

        submit(in_flight)
        for _, (tile, (path, glb), s) in pending:
            if on_workers is None:
                _sylva.write_files(staging, [(path, glb)])
            tiles.append(tile)
            seconds["tiles"].append(s)
            submit(1)
        summary, files = job.finish(tiles)
        _sylva.write_files(staging, files)
        _sylva.commit(staging, os.fspath(out))
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    summary["task_seconds"] = seconds
    summary["driver_seconds"] = {
        "plan": planned,
        "grow": grown_at - t0 - planned,
        "tiles": time.perf_counter() - grown_at,
    }
    return summary


def estimate(
    summary: Dict[str, Any],
    *,
    trees: int,
    epochs: int,
    workers: int,
) -> Dict[str, float]:
    """The time a city of ``trees`` trees at ``epochs`` epochs would take on ``workers``
    workers, from a measured run's ``summary`` (from :func:`city`, same region and options).

    The basis, each term from the measured run:

    - growth: the grown trees a city shares are bounded by its species, age classes and
      seed variants, not by its trees; a city far larger than the measured one grows at most
      every species' classes. Its growth tasks are taken as the measured ones scaled by the
      classes the larger city would add (at most all 15 a species has), spread over the
      workers but never shorter than the longest task;
    - tiles: each tree is drawn once per level of its epoch's quadtree; tile seconds per tree
      and level, times trees x epochs x levels (log4 of trees over 250, plus one), over the
      workers;
    - planning on the driver: its measured seconds per tree, times trees.
    """
    import math

    measured_trees = max(1, int(summary["trees"]) + int(summary["stumps"]))
    measured_epochs = max(1, len(summary["epochs"]))
    growth = summary["task_seconds"]["growth"]
    tiles = summary["task_seconds"]["tiles"]
    depth = lambda n: math.ceil(math.log(max(n / 250.0, 1.0), 4)) + 1  # noqa: E731
    tree_levels = sum(e["trees"] * (e["depth"] + 1) for e in summary["epochs"])
    per_tree_level = sum(tiles) / max(1, tree_levels)
    # Prototypes: the measured city's, and at most every class of every species it grows.
    tasks = max(1, len(growth))
    classes_now = int(summary["prototypes"]) / tasks
    # Sylva's 15 age classes (`sylva_city::trees::plan::AGE_CLASSES`).
    classes_full = 15.0
    scale = max(1.0, classes_full / max(classes_now, 1.0))
    growth_total = sum(growth) * scale
    growth_time = max(growth_total / workers, max(growth, default=0.0) * scale)
    tile_time = per_tree_level * trees * epochs * depth(trees) / workers
    plan_time = summary["driver_seconds"]["plan"] / measured_trees * trees * epochs / measured_epochs
    return {
        "growth_s": growth_time,
        "tiles_s": tile_time,
        "plan_s": plan_time,
        "total_s": growth_time + tile_time + plan_time,
        "growth_task_s_total": growth_total,
        "tile_s_per_tree_level": per_tree_level,
        "levels": float(depth(trees)),
    }
