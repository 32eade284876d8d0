import os
import shutil
import subprocess

import pytest


@pytest.fixture(scope="session")
def sylva_bin():
    """The `sylva` CLI built from the same tree as the wheel: SYLVA_BIN, else the README's build
    (target/debug), else a release build."""
    target = os.path.join(os.path.dirname(__file__), "..", "..", "..", "target")
    candidates = [os.environ.get("SYLVA_BIN")] if os.environ.get("SYLVA_BIN") else [
        os.path.join(target, "debug", "sylva"),
        os.path.join(target, "release", "sylva"),
    ]
    for path in candidates:
        if os.path.exists(path):
            return os.path.abspath(path)
    pytest.skip(f"no sylva binary at {' or '.join(candidates)}; build it with cargo build --bin sylva")


@pytest.fixture(scope="session")
def demo_csv(tmp_path_factory, sylva_bin):
    """A small synthetic inventory (census layout), written by `sylva city-demo`: 24 rows, 21 of
    them trees of 13 species (the demo breaks some rows on purpose), in one tile per epoch.
    Each city grown from it takes some 11 s on 2 cores (30 rows took 18 s: the oldest trees
    set the time), and the tests grow it five times."""
    path = tmp_path_factory.mktemp("inventory") / "trees.csv"
    subprocess.run(
        [sylva_bin, "city-demo", "-o", str(path), "--trees", "24", "--region", "InlVal"],
        check=True,
        capture_output=True,
    )
    return path
