# SPDX-License-Identifier: MIT
"""Writes this folder's blender_* files: one small scene exported by
Blender's own exporters in every format it writes that the mesh loader
reads, and the scene's world-space triangles as Blender sees them
(blender_truth.json), against which test_mesh.cpp checks every file.

The scene: a rotated, scaled cube; an icosphere parented to it (a nested
node transformation); a tilted cone. All faces are triangulated first, so
every format holds the same triangles.

Run (Blender 3.4.1, Debian 12's `blender` package, wrote the files here):
    blender -b --factory-startup --python make_with_blender.py -- OUT_DIR
"""
import json
import math
import sys
from pathlib import Path

import bmesh
import bpy

out = Path(sys.argv[sys.argv.index("--") + 1]).resolve()
out.mkdir(parents=True, exist_ok=True)

bpy.ops.wm.read_factory_settings(use_empty=True)


def triangulated(obj):
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bmesh.ops.triangulate(bm, faces=bm.faces[:])
    bm.to_mesh(obj.data)
    bm.free()
    return obj


bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.3, -0.2, 0.1), rotation=(0.3, 0.5, 0.7))
cube = triangulated(bpy.context.active_object)
cube.name = "cube"
cube.scale = (0.6, 0.4, 0.5)
bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=1, radius=0.35, location=(-0.6, 0.4, 0.2))
ico = triangulated(bpy.context.active_object)
ico.name = "ico"
bpy.ops.mesh.primitive_cone_add(vertices=7, radius1=0.3, depth=0.8, location=(0.2, 0.7, -0.5),
                                rotation=(1.0, 0.0, 0.4))
cone = triangulated(bpy.context.active_object)
cone.name = "cone"
cone.scale = (1.0, 0.5, 1.2)
bpy.context.view_layer.update()
world = ico.matrix_world.copy()
ico.parent = cube
ico.matrix_world = world  # keeps its place; its node now sits below the cube's
bpy.context.view_layer.update()

triangles = []
for obj in (cube, ico, cone):
    m = obj.data
    m.calc_loop_triangles()
    for t in m.loop_triangles:
        triangles.append([list(obj.matrix_world @ m.vertices[v].co) for v in t.vertices])
(out / "blender_truth.json").write_text(json.dumps({
    "tool": f"Blender {bpy.app.version_string}", "triangles": triangles}, indent=None))

bpy.ops.object.select_all(action="SELECT")
bpy.ops.export_mesh.ply(filepath=str(out / "blender_ascii.ply"), use_ascii=True, use_normals=False,
                        use_uv_coords=False, use_colors=False)
bpy.ops.export_mesh.ply(filepath=str(out / "blender_binary.ply"), use_ascii=False, use_normals=False,
                        use_uv_coords=False, use_colors=False)
bpy.ops.export_mesh.stl(filepath=str(out / "blender_ascii.stl"), ascii=True)
bpy.ops.export_mesh.stl(filepath=str(out / "blender_binary.stl"), ascii=False)
bpy.ops.wm.obj_export(filepath=str(out / "blender.obj"), export_materials=False, export_uv=False,
                      export_normals=False)
bpy.ops.export_scene.gltf(filepath=str(out / "blender.glb"), export_format="GLB")
bpy.ops.export_scene.gltf(filepath=str(out / "blender_embedded.gltf"), export_format="GLTF_EMBEDDED")
bpy.ops.export_scene.fbx(filepath=str(out / "blender.fbx"))
bpy.ops.export_scene.x3d(filepath=str(out / "blender.x3d"))
try:
    bpy.ops.wm.collada_export(filepath=str(out / "blender.dae"))
except (AttributeError, RuntimeError) as e:
    print("no Collada exporter in this Blender:", e)
print("wrote", sorted(p.name for p in out.iterdir()))
