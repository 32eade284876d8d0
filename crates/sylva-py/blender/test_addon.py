"""Blender in background mode installs the add-on's zip from the preferences, adds Sylva trees
through Add > Sylva tree, and checks their polygons and materials against Sylva's own counts.

    blender -b --factory-startup --python-exit-code 1 --python test_addon.py -- sylva_tree.zip

It also runs under PyPI's `bpy` (Blender as a Python module): `python test_addon.py -- ZIP`.
"""

import os
import sys

# Run as a script (under PyPI's bpy), this folder heads sys.path and would shadow the
# installed add-on with its source.
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:] = [p for p in sys.path if os.path.abspath(p or ".") != HERE]

import bpy  # noqa: E402

zip_path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
bpy.ops.preferences.addon_enable(module="sylva_tree")
assert "sylva_tree_add" in dir(bpy.ops.mesh), "the add-on did not register its operator"
menu = [getattr(f, "__module__", "") for f in bpy.types.VIEW3D_MT_add._dyn_ui_initialize()]
assert "sylva_tree" in menu, f"no Sylva entry in Add: {menu}"

# The installed copy (enabling imported it), never a source tree on sys.path.
sylva_tree = sys.modules["sylva_tree"]
assert "scripts" in sylva_tree.__file__ and "addons" in sylva_tree.__file__, sylva_tree.__file__
sylva = sylva_tree._sylva()


def check(op_kwargs, model):
    before = set(bpy.data.objects)
    result = bpy.ops.mesh.sylva_tree_add(**op_kwargs)
    assert result == {"FINISHED"}, result
    (obj,) = set(bpy.data.objects) - before
    mesh = obj.data
    polygons, vertices = len(mesh.polygons), len(mesh.vertices)
    assert polygons == model.triangles, (polygons, model.triangles)
    assert vertices == model.vertices, (vertices, model.vertices)
    assert all(p.loop_total == 3 for p in mesh.polygons[:1000])
    names = [m.name for m in mesh.materials]
    assert len(names) == len(model.arrays()), names
    assert any("bark" in n for n in names) and any("leaves" in n for n in names), names
    used = {p.material_index for p in mesh.polygons}
    assert used == set(range(len(names))), used
    assert not mesh.validate(verbose=True), "Blender found invalid geometry"
    height = max(v.co.z for v in mesh.vertices)
    print(f"OK {obj.name}: {polygons} polygons, {vertices} vertices, materials {names}, "
          f"{height:.1f} m tall")
    return obj


check({"species": "quaking_aspen", "seed": 2, "quality": 0.5},
      sylva.generate("quaking_aspen", seed=2, quality=0.5))
check({"species": "black_tupelo", "seed": 1, "branches": 20, "overrides": "Ratio=0.02"},
      sylva.generate("black_tupelo", seed=1, set={"1Branches": 20, "Ratio": 0.02}))
check({"kind": "STREET", "code": "PLAC", "region": "InlVal", "age": 15, "seed": 0},
      sylva.grow("PLAC", region="InlVal", age=15, seed=0, season="summer"))
# Sylva's error reaches the user as the operator's report (in background mode, an exception).
try:
    bpy.ops.mesh.sylva_tree_add(species="quaking_aspen", overrides="Bogus=1")
    raise AssertionError("a bad parameter was taken")
except RuntimeError as e:
    assert "Sylva: set Bogus=1: unknown parameter" in str(e), e
print(f"Blender {bpy.app.version_string}: the Sylva add-on passed")
