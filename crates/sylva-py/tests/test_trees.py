"""The wheel's trees: arrays that make a sound mesh, GLB bytes a glTF reader takes, grown
dimensions against the equations, and errors as exceptions."""

import json
import struct
import threading
import time

import numpy as np
import pytest

import sylva


def test_generate_gives_a_sound_mesh_as_numpy_arrays():
    tree = sylva.generate("quaking_aspen", seed=3)
    arrays = tree.arrays()
    assert set(arrays) == {"bark", "leaves"}
    total = 0
    for name, part in arrays.items():
        p, n, uv, ix = part["positions"], part["normals"], part["uvs"], part["indices"]
        assert p.dtype == np.float32 and p.ndim == 2 and p.shape[1] == 3
        assert n.shape == p.shape and uv.shape == (p.shape[0], 2)
        assert ix.dtype == np.uint32 and ix.shape[1] == 3
        assert ix.max() < p.shape[0], name
        lengths = np.linalg.norm(n, axis=1)
        assert np.allclose(lengths, 1.0, atol=1e-3), name
        total += ix.shape[0]
    assert total == tree.triangles
    # An aspen some metres tall standing on the ground, Z up.
    z = arrays["bark"]["positions"][:, 2]
    assert abs(z.min()) < 0.5
    s = tree.summary
    assert 8.0 < s["height_m"] < 30.0
    assert abs(z.max() - s["height_m"]) < 0.05 * s["height_m"]
    assert s["stems_per_level"][0] == 1 and s["leaves"] > 1000


def test_the_same_seed_gives_the_same_tree_and_another_seed_another():
    a = sylva.generate("black_tupelo", seed=7).arrays()["bark"]["positions"]
    b = sylva.generate("black_tupelo", seed=7).arrays()["bark"]["positions"]
    c = sylva.generate("black_tupelo", seed=8).arrays()["bark"]["positions"]
    assert np.array_equal(a, b)
    assert a.shape != c.shape or not np.array_equal(a, c)


def test_set_overrides_a_parameter():
    few = sylva.generate("quaking_aspen", set={"1Branches": 10}, leaves=False)
    many = sylva.generate("quaking_aspen", set={"1Branches": 60}, leaves=False)
    assert few.summary["stems_per_level"][1] == 10
    assert many.summary["stems_per_level"][1] == 60
    assert "leaves" not in few.arrays()


def test_glb_bytes_are_a_gltf_file():
    glb = sylva.generate("quaking_aspen", quality=0.5).glb()
    magic, version, length = struct.unpack_from("<4sII", glb, 0)
    assert magic == b"glTF" and version == 2 and length == len(glb)
    chunk_length, chunk_type = struct.unpack_from("<II", glb, 12)
    assert chunk_type == 0x4E4F534A  # JSON
    doc = json.loads(glb[20 : 20 + chunk_length])
    assert {m["name"] for m in doc["materials"]} >= {"bark", "leaves"}
    assert doc["asset"]["version"] == "2.0"


def test_grow_holds_the_equations_and_reports_the_street():
    oak = sylva.grow("PLAC", region="InlVal", age=20)
    s = oak.summary
    assert s["region"] == "InlVal" and "plane" in s["common_name"].lower()
    for key in ("height", "crown_diameter", "dbh"):
        unit = "_cm" if key == "dbh" else "_m"
        model, measured = s[key + unit], s[key + "_measured" + unit]
        assert measured > 0 and abs(model / measured - 1) < 0.2, (key, model, measured)
    street = s["street"]
    assert street["co2_stored_kg"] > street["co2_sequestered_kg"] > 0
    assert street["interception_m3"] > 0 and street["value_usd"]["stormwater"] > 0
    assert oak.arrays()["leaves"]["positions"].shape[0] > 1000
    # Older is bigger.
    assert sylva.grow("PLAC", region="InlVal", age=40).summary["dbh_cm"] > s["dbh_cm"]


def test_rank_gives_the_clis_rows(sylva_bin, tmp_path):
    """`sylva.rank` and `sylva rank --json` make the same request of the same library and write
    the same record: the rows are equal, field for field."""
    import os
    import subprocess

    repo = os.path.join(os.path.dirname(__file__), "..", "..", "..")
    site = os.path.join(repo, "sites", "narrow-under-wires.toml")
    rows = sylva.rank("InlVal", years=6, species=["PLAC", "LAIN"], site=site)
    run = subprocess.run(
        [sylva_bin, "rank", "--region", "InlVal", "--years", "6", "--species", "PLAC",
         "--species", "LAIN", "--site", site, "--json"],
        check=True, capture_output=True, text=True,
    )
    cli = [json.loads(line) for line in run.stdout.splitlines()]
    assert [r["species"] for r in rows] == [r["species"] for r in cli]
    assert rows == cli
    assert rows[0]["ranked_by"] == "this site" and rows[0]["per_tree_planted"]
    with pytest.raises(sylva.SylvaError, match="pruning `sometimes`"):
        sylva.rank("InlVal", years=2, pruning="sometimes")


def test_errors_are_sylva_errors_naming_what_is_wrong():
    with pytest.raises(sylva.SylvaError, match="nope"):
        sylva.generate("nope")
    with pytest.raises(sylva.SylvaError, match="Bogus"):
        sylva.generate("quaking_aspen", set={"Bogus": 1})
    with pytest.raises(sylva.SylvaError, match="Atlantis"):
        sylva.grow("PLAC", region="Atlantis", age=5)
    with pytest.raises(sylva.SylvaError, match="quality"):
        sylva.generate("quaking_aspen", quality=-1)
    with pytest.raises(sylva.SylvaError, match="age -3: expected 0 to 300 years"):
        sylva.grow("PLAC", region="InlVal", age=-3)
    with pytest.raises(sylva.SylvaError, match="no-such.toml"):
        sylva.grow("PLAC", region="InlVal", age=5, site="no-such.toml")


def test_species_lists():
    assert "quaking_aspen" in sylva.species()
    codes = {(s["code"], s["region"]) for s in sylva.street_species()}
    assert ("PLAC", "InlVal") in codes and len(codes) > 200


def test_a_long_call_lets_other_threads_run():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    t = threading.Thread(target=tick)
    t.start()
    t0 = time.perf_counter()
    sylva.grow("PLAC", region="InlVal", age=30)
    t1 = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if t0 < x < t1]
    # Holding the GIL for the whole growth would allow no tick in between.
    assert len(during) >= 3, (len(during), t1 - t0)
