"""Cities from Python: a file or a pandas frame tiled in this process, and the same city
tiled across a local Dask cluster of two workers, byte for byte as `sylva city` writes it."""

import hashlib
import json
import os
import subprocess

import pytest

import sylva


def digest(folder):
    """Every file under `folder` and its SHA-256."""
    out = {}
    for root, _, files in os.walk(folder):
        for f in files:
            path = os.path.join(root, f)
            with open(path, "rb") as fh:
                out[os.path.relpath(path, folder)] = hashlib.sha256(fh.read()).hexdigest()
    return out


OPTIONS = dict(years=[0, 8], variants=1, seed=5)


@pytest.fixture(scope="module")
def cli_city(tmp_path_factory, sylva_bin, demo_csv):
    out = tmp_path_factory.mktemp("cli") / "tiles"
    subprocess.run(
        [sylva_bin, "city", str(demo_csv), "-o", str(out), "--years", "0,8", "--variants", "1", "--seed", "5"],
        check=True,
        capture_output=True,
    )
    return out


def test_city_from_a_file_is_the_cli_s(tmp_path, demo_csv, cli_city):
    summary = sylva.city(demo_csv, tmp_path / "tiles", **OPTIONS)
    assert summary["trees"] > 20 and len(summary["epochs"]) == 2
    assert digest(tmp_path / "tiles") == digest(cli_city)


def test_city_from_a_pandas_frame(tmp_path, demo_csv, cli_city):
    pd = pytest.importorskip("pandas")
    frame = pd.read_csv(demo_csv, dtype=str, keep_default_na=False)
    summary = sylva.city(frame, tmp_path / "tiles", **OPTIONS)
    with open(cli_city / "summary.json") as f:
        cli = json.load(f)
    assert summary["trees"] == cli["trees"] and summary["stumps"] == cli["stumps"]
    # The tiles are the same trees: only the file the rows were read from differs.
    a, b = digest(tmp_path / "tiles"), digest(cli_city)
    assert set(a) == set(b)
    assert {k: v for k, v in a.items() if k.endswith(".glb")} == {
        k: v for k, v in b.items() if k.endswith(".glb")
    }


def test_city_errors_name_the_setting(tmp_path, demo_csv):
    with pytest.raises(sylva.SylvaError, match="variants"):
        sylva.city(demo_csv, tmp_path / "a", variants=0)
    with pytest.raises(sylva.SylvaError, match="crs"):
        sylva.city(demo_csv, tmp_path / "b", crs="EPSG:abc")
    with pytest.raises(sylva.SylvaError, match="columns"):
        sylva.city(demo_csv, tmp_path / "c", columns={"colour": "x"})
    with pytest.raises(sylva.SylvaError, match="`species` is 3"):
        sylva.city(demo_csv, tmp_path / "e", columns={"species": 3})
    with pytest.raises(sylva.SylvaError, match="missing.csv"):
        sylva.city(tmp_path / "missing.csv", tmp_path / "d")
    assert not os.path.exists(tmp_path / "a") and not os.path.exists(tmp_path / "d")


def test_dask_two_workers_write_the_cli_s_bytes(tmp_path, demo_csv, cli_city):
    distributed = pytest.importorskip("distributed")
    import sylva.dask

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        summary = sylva.dask.city(demo_csv, tmp_path / "driver", client=client, **OPTIONS)
        sylva.dask.city(
            demo_csv, tmp_path / "workers", client=client, write="workers", in_flight=3, **OPTIONS
        )
        workers = {w["id"] for w in client.scheduler_info()["workers"].values()}
    assert len(workers) == 2
    expected = digest(cli_city)
    assert len(expected) > 20
    assert digest(tmp_path / "driver") == expected
    assert digest(tmp_path / "workers") == expected
    seconds = summary["task_seconds"]
    assert len(seconds["growth"]) >= 3 and len(seconds["tiles"]) == sum(
        e["tiles"] for e in summary["epochs"]
    )
    guess = sylva.dask.estimate(summary, trees=1_000_000, epochs=4, workers=16)
    assert guess["total_s"] > guess["tiles_s"] > 0 and guess["levels"] >= 6
