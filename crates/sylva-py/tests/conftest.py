import os
import shutil
import subprocess

import pytest


@pytest.fixture(scope="session")
def sylva_bin():
    """The `sylva` CLI built from the same tree as the wheel (SYLVA_BIN, else target/release)."""
    path = os.environ.get("SYLVA_BIN") or os.path.join(
        os.path.dirname(__file__), "..", "..", "..", "target", "release", "sylva"
    )
    if not os.path.exists(path):
        pytest.skip(f"no sylva binary at {path}; build it with cargo build --release -p sylva-cli")
    return os.path.abspath(path)


@pytest.fixture(scope="session")
def demo_csv(tmp_path_factory, sylva_bin):
    """A small synthetic inventory (census layout), written by `sylva city-demo`."""
    path = tmp_path_factory.mktemp("inventory") / "trees.csv"
    subprocess.run(
        [sylva_bin, "city-demo", "-o", str(path), "--trees", "60", "--region", "InlVal"],
        check=True,
        capture_output=True,
    )
    return path
