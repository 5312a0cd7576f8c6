"""Render a Radiant JSON scene with Blender Cycles, an independent, established
path tracer, to check `radiant render --method path` against it.

Usage (Blender is not a Radiant dependency; `apt-get install blender`):

    blender -b --factory-startup -P tools/cycles_reference.py -- \
        scenes/cornell-box/scene.json cycles.exr --spp 1024 --size 256

Only what Radiant's bundled Cornell scenes use is translated: quad, triangle
and sphere objects; lambertian, mirror and dielectric materials; one-sided
emission (Cycles emits from both sides, so the back is masked with the
Backfacing output, matching Radiant's convention). Cycles is set up to be
unbiased and comparable: box pixel filter of one pixel, no clamping, no
denoising, no caustic filtering, deep bounce limits, linear (Standard) view
transform, 32-bit float EXR in linear Rec.709 — Radiant's bands.
"""
import json
import math
import sys

import bpy
from mathutils import Matrix, Vector

argv = sys.argv[sys.argv.index("--") + 1:]
scene_path, output_path = argv[0], argv[1]
spp = int(argv[argv.index("--spp") + 1]) if "--spp" in argv else 1024
size = int(argv[argv.index("--size") + 1]) if "--size" in argv else 256
# --bounces N: Cycles counts indirect bounces (0 = direct light only) = radiant --max-depth N+1
bounces = int(argv[argv.index("--bounces") + 1]) if "--bounces" in argv else 256

data = json.load(open(scene_path))
units = {"metres": 1, "meters": 1, "m": 1, "centimetres": 0.01, "cm": 0.01, "millimetres": 0.001,
         "millimeters": 0.001, "mm": 0.001}[data.get("units", "metres")]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = spp
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.pixel_filter_type = "BOX"
scene.cycles.filter_width = 1.0
scene.cycles.sample_clamp_direct = 0.0
scene.cycles.sample_clamp_indirect = 0.0
scene.cycles.blur_glossy = 0.0
scene.cycles.caustics_reflective = True
scene.cycles.caustics_refractive = True
for attr in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces", "transparent_max_bounces"):
    setattr(scene.cycles, attr, bounces)
scene.cycles.seed = 1
scene.render.resolution_x = size
scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = 0
scene.view_settings.gamma = 1
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"
world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
scene.world = world


def rgb(value, default):
    if value is None:
        value = default
    if isinstance(value, (int, float)):
        value = [value] * 3
    return (value[0], value[1], value[2], 1.0)


def make_material(name, spec):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    kind = spec.get("type", "lambertian")
    if kind == "mirror":
        surface = nodes.new("ShaderNodeBsdfGlossy")
        surface.distribution = "SHARP"
        surface.inputs["Color"].default_value = rgb(spec.get("reflectance"), 1.0)
    elif kind == "dielectric":
        surface = nodes.new("ShaderNodeBsdfGlass")
        surface.distribution = "SHARP"
        surface.inputs["IOR"].default_value = spec.get("ior", 1.5)
        surface.inputs["Color"].default_value = rgb(spec.get("transmittance"), 1.0)
    else:
        surface = nodes.new("ShaderNodeBsdfDiffuse")
        surface.inputs["Color"].default_value = rgb(spec.get("reflectance"), 0.5)
    shader = surface.outputs[0]
    emission = spec.get("emission")
    if emission is not None:
        emit = nodes.new("ShaderNodeEmission")
        emit.inputs["Color"].default_value = rgb(emission, 0.0)
        emit.inputs["Strength"].default_value = 1.0
        black = nodes.new("ShaderNodeMixShader")  # one-sided: nothing from the back
        geometry = nodes.new("ShaderNodeNewGeometry")
        links.new(geometry.outputs["Backfacing"], black.inputs["Fac"])
        links.new(emit.outputs[0], black.inputs[1])
        add = nodes.new("ShaderNodeAddShader")
        links.new(shader, add.inputs[0])
        links.new(black.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    links.new(shader, out.inputs["Surface"])
    return mat


materials = {name: make_material(name, spec) for name, spec in data.get("materials", {}).items()}
materials.setdefault("default", make_material("default", {}))


def add_mesh(name, vertices, faces, material, smooth=False):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata([Vector(v) * units for v in vertices], [], faces)
    mesh.update()
    for polygon in mesh.polygons:
        polygon.use_smooth = smooth
    obj = bpy.data.objects.new(name, mesh)
    obj.data.materials.append(materials[material])
    scene.collection.objects.link(obj)


for index, obj in enumerate(data["objects"]):
    kind, name, material = obj["type"], obj.get("name", f"object{index}"), obj.get("material", "default")
    if "transform" in obj:
        raise SystemExit(f"{name}: transforms are not translated by this script")
    if kind in ("quad", "triangle"):
        add_mesh(name, obj["vertices"], [list(range(len(obj["vertices"])))], material)
    elif kind == "sphere":
        c, r = Vector(obj["center"]), obj["radius"]
        segments = max(64, obj.get("segments", 48))
        bpy.ops.mesh.primitive_uv_sphere_add(segments=segments, ring_count=segments // 2, radius=r * units,
                                             location=c * units)
        sphere = bpy.context.active_object
        bpy.ops.object.shade_smooth()
        sphere.data.materials.append(materials[material])
    else:
        raise SystemExit(f"{name}: object type {kind} is not translated by this script")

camera_spec = data["camera"]
eye = Vector(camera_spec["eye"]) * units
target = Vector(camera_spec["target"]) * units
up = Vector(camera_spec.get("up", [0, 1, 0]))
forward = (target - eye).normalized()
right = forward.cross(up).normalized()
true_up = right.cross(forward)
camera_data = bpy.data.cameras.new("camera")
camera_data.sensor_fit = "VERTICAL"
camera_data.angle_y = math.radians(camera_spec["fov"])
camera_data.clip_start = 1e-4
camera_data.clip_end = 1e4
camera = bpy.data.objects.new("camera", camera_data)
rotation = Matrix((right, true_up, -forward)).transposed()  # columns: x right, y up, z back
camera.matrix_world = Matrix.Translation(eye) @ rotation.to_4x4()
scene.collection.objects.link(camera)
scene.camera = camera

scene.render.filepath = output_path
bpy.ops.render.render(write_still=True)
