"""`sylva draw -o tree.dxf` read back by ezdxf, as a landscape architect's CAD would read it:
the plan and elevation blocks, the four layers, metres, and the drawing as tall and wide as the
grown tree (issue Z, first step)."""

import json
import subprocess

import pytest

ezdxf = pytest.importorskip("ezdxf")
from ezdxf import bbox  # noqa: E402


def test_a_grown_london_plane_reads_back_in_metres_at_its_size(sylva_bin, tmp_path):
    path = tmp_path / "plane.dxf"
    subprocess.run(
        [sylva_bin, "draw", "PLAC", "--region", "InlVal", "--age", "30", "-o", str(path)],
        check=True, capture_output=True,
    )
    grown = subprocess.run(
        [sylva_bin, "grow", "PLAC", "--region", "InlVal", "--from", "30", "--to", "30",
         "--no-pictures", "--json", "-o", str(tmp_path / "grown")],
        check=True, capture_output=True, text=True,
    )
    record = json.loads(grown.stdout.splitlines()[0])
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 6  # metres
    blocks = [b.name for b in doc.blocks if not b.name.startswith("*")]
    assert sorted(b.rsplit("-", 1)[1] for b in blocks) == ["FRONT", "PLAN", "SIDE"], blocks
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"TREE-TRUNK", "TREE-BRANCHES", "TREE-CROWN", "TREE-LEAVES"} <= layers
    inserts = [e.dxf.name for e in doc.modelspace().query("INSERT")]
    assert sorted(inserts) == sorted(blocks)
    front = bbox.extents(doc.blocks.get(next(b for b in blocks if b.endswith("-FRONT"))))
    height = front.extmax.y - front.extmin.y
    assert abs(height / record["height_m"] - 1) < 0.05, (height, record["height_m"])
    plan = bbox.extents(doc.blocks.get(next(b for b in blocks if b.endswith("-PLAN"))))
    across = ((plan.extmax.x - plan.extmin.x) + (plan.extmax.y - plan.extmin.y)) / 2
    assert abs(across / record["crown_diameter_m"] - 1) < 0.15, (across, record["crown_diameter_m"])
