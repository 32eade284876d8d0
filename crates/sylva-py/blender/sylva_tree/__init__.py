"""Sylva for Blender: Add > Sylva tree.

A Weber & Penn tree by species, seed and its main parameters, or a street tree grown by the
USDA Urban Tree Database's equations to an age, built as a mesh with bark and leaf materials
straight from Sylva's numpy arrays (no file in between).

Sylva itself comes in the add-on's zip (``vendor/``, unpacked from the wheel by
``build_addon.py``) unless a ``sylva`` package is already importable. Blender's Python needs
numpy: Blender's own builds carry it; Debian's Blender takes it from ``python3-numpy``.
"""

import os
import sys

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

bl_info = {
    "name": "Sylva tree",
    "author": "Sylva",
    "version": (0, 1, 0),
    "blender": (2, 93, 0),
    "location": "View3D > Add > Sylva tree",
    "description": "Realistic trees: Weber & Penn species, or street trees grown to an age",
    "category": "Add Mesh",
}

_VENDOR = os.path.join(os.path.dirname(__file__), "vendor")


def _sylva():
    """The sylva package: the one already importable, else the add-on's own copy."""
    try:
        import sylva  # noqa: F401
    except ImportError:
        if _VENDOR not in sys.path:
            sys.path.insert(0, _VENDOR)
    import sylva

    return sylva


def _species_items(self, context):
    return [(s, s.replace("_", " ").title(), "") for s in _sylva().species()]


def build_object(context, model):
    """A mesh object of `model` (a sylva.Model): one mesh, a material per part."""
    import numpy as np

    parts = [(name, arrays) for name, arrays in model.arrays().items()]
    positions = np.concatenate([a["positions"] for _, a in parts]).astype(np.float32)
    offsets = np.cumsum([0] + [a["positions"].shape[0] for _, a in parts])
    triangles = np.concatenate(
        [a["indices"].astype(np.int64) + offsets[k] for k, (_, a) in enumerate(parts)]
    )
    uvs = np.concatenate([a["uvs"] for _, a in parts]).astype(np.float32)
    normals = np.concatenate([a["normals"] for _, a in parts]).astype(np.float32)
    material_index = np.concatenate(
        [np.full(a["indices"].shape[0], k, dtype=np.int32) for k, (_, a) in enumerate(parts)]
    )

    mesh = bpy.data.meshes.new(model.name)
    mesh.vertices.add(positions.shape[0])
    mesh.vertices.foreach_set("co", positions.ravel())
    mesh.loops.add(triangles.size)
    mesh.loops.foreach_set("vertex_index", triangles.ravel().astype(np.int32))
    mesh.polygons.add(triangles.shape[0])
    mesh.polygons.foreach_set("loop_start", np.arange(0, triangles.size, 3, dtype=np.int32))
    if bpy.app.version < (4, 0, 0):
        # Blender 4 derives each face's loop count from the next face's start.
        mesh.polygons.foreach_set("loop_total", np.full(triangles.shape[0], 3, dtype=np.int32))
    mesh.polygons.foreach_set("material_index", material_index)
    mesh.polygons.foreach_set("use_smooth", np.ones(triangles.shape[0], dtype=bool))
    uv_layer = mesh.uv_layers.new(name="UVMap")
    uv_layer.data.foreach_set("uv", uvs[triangles.ravel()].ravel())
    mesh.update()
    if hasattr(mesh, "use_auto_smooth"):
        mesh.use_auto_smooth = True  # custom normals need it before Blender 4.1
    mesh.normals_split_custom_set_from_vertices(normals)

    colours = model.materials
    for name, _ in parts:
        mat = bpy.data.materials.new(f"{model.name} {name}")
        mat.use_nodes = True
        bsdf = mat.node_tree.nodes.get("Principled BSDF")
        if bsdf is not None:
            bsdf.inputs["Base Color"].default_value = colours[name]
            bsdf.inputs["Roughness"].default_value = 0.9 if name == "bark" else 0.6
        mat.diffuse_color = colours[name]
        # Leaves are single cards, seen from both sides.
        mat.use_backface_culling = False
        mesh.materials.append(mat)

    obj = bpy.data.objects.new(model.name, mesh)
    obj["sylva_summary"] = str(model.summary)
    context.collection.objects.link(obj)
    obj.location = context.scene.cursor.location
    for other in context.selected_objects:
        other.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj
    return obj


class SYLVA_OT_tree_add(bpy.types.Operator):
    """Add a Sylva tree: a Weber & Penn species, or a street tree grown to an age"""

    bl_idname = "mesh.sylva_tree_add"
    bl_label = "Sylva tree"
    bl_options = {"REGISTER", "UNDO"}

    kind: EnumProperty(
        name="Tree",
        items=[
            ("SPECIES", "Species", "A Weber & Penn tree of a species"),
            ("STREET", "Street tree", "A street tree grown by the Urban Tree Database's equations"),
        ],
        default="SPECIES",
    )
    species: EnumProperty(name="Species", items=_species_items)
    seed: IntProperty(name="Seed", default=0, min=0)
    quality: FloatProperty(name="Quality", default=1.0, min=0.1, max=4.0)
    levels: IntProperty(name="Levels", description="Branching levels (0: the species')", default=0, min=0, max=4)
    leaves: BoolProperty(name="Leaves", default=True)
    branches: IntProperty(name="Branches", description="First-level branches (0: the species')", default=0, min=0, max=500)
    overrides: StringProperty(
        name="Parameters", description="More parameters, e.g. 'Ratio=0.02, 0Scale=15'", default=""
    )
    code: StringProperty(name="Species code", description="Urban Tree Database code or name", default="PLAC")
    region: StringProperty(name="Region", default="InlVal")
    age: FloatProperty(name="Age", default=20.0, min=1.0, max=200.0)
    season: EnumProperty(
        name="Season",
        items=[(s, s.title(), "") for s in ("summer", "spring", "autumn", "winter")],
        default="summer",
    )

    def draw(self, context):
        col = self.layout.column()
        col.prop(self, "kind")
        if self.kind == "SPECIES":
            for name in ("species", "seed", "quality", "levels", "leaves", "branches", "overrides"):
                col.prop(self, name)
        else:
            for name in ("code", "region", "age", "season", "seed"):
                col.prop(self, name)

    def make(self):
        sylva = _sylva()
        if self.kind == "STREET":
            return sylva.grow(self.code, region=self.region, age=self.age, seed=self.seed, season=self.season)
        params = {}
        if self.branches:
            params["1Branches"] = float(self.branches)
        for item in filter(None, (s.strip() for s in self.overrides.split(","))):
            name, _, value = item.partition("=")
            try:
                params[name.strip()] = float(value)
            except ValueError:
                raise sylva.SylvaError(f"parameter {item!r}: expected NAME=NUMBER")
        return sylva.generate(
            self.species,
            seed=self.seed,
            quality=self.quality,
            levels=self.levels or None,
            leaves=self.leaves,
            set=params,
        )

    def execute(self, context):
        try:
            model = self.make()
        except Exception as e:  # Sylva's message, shown in Blender's status bar
            self.report({"ERROR"}, f"Sylva: {e}")
            return {"CANCELLED"}
        build_object(context, model)
        return {"FINISHED"}


def _menu(self, context):
    self.layout.operator(SYLVA_OT_tree_add.bl_idname, text="Sylva tree", icon="OUTLINER_OB_FORCE_FIELD")


def register():
    bpy.utils.register_class(SYLVA_OT_tree_add)
    bpy.types.VIEW3D_MT_add.append(_menu)
    bpy.types.VIEW3D_MT_mesh_add.append(_menu)


def unregister():
    bpy.types.VIEW3D_MT_mesh_add.remove(_menu)
    bpy.types.VIEW3D_MT_add.remove(_menu)
    bpy.utils.unregister_class(SYLVA_OT_tree_add)
