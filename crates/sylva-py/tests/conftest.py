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
    """A small synthetic inventory (census layout), written by `sylva city-demo`: 30 rows, 27 of
    them trees (the demo breaks some rows on purpose), in one tile per epoch. Each city grown
    from it takes some 25 s on 2 cores, and the tests grow it five times."""
    path = tmp_path_factory.mktemp("inventory") / "trees.csv"
    subprocess.run(
        [sylva_bin, "city-demo", "-o", str(path), "--trees", "30", "--region", "InlVal"],
        check=True,
        capture_output=True,
    )
    return path
