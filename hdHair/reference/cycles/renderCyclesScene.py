# Renders a scene hdHair exported (hdHair/reference/CyclesScene.h) with
# Blender's Cycles, headless:
#   blender -b --factory-startup --python-exit-code 2 -P renderCyclesScene.py -- scene.json out.exr
# hdhair-record --reference cycles runs it; docs/cycles-reference.md says how
# every prim, light and setting maps. Writes a 32-bit float RGBA EXR with
# pre-multiplied alpha over a transparent background, scene-linear in the
# space the scene's colours are in (Cycles does not convert them: the view
# transform is Standard and only the display formats, written by
# hdhair-record, are colour-managed). Prints "hdhair-cycles: done seconds=T"
# at the end, or "hdhair-cycles: error: ..." and exits 2.

import array
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix


def fail(message):
    print("hdhair-cycles: error: " + message, flush=True)
    sys.exit(2)


class Blob:
    """scene.bin: the arrays scene.json points into."""

    def __init__(self, path):
        with open(path, "rb") as f:
            self.data = f.read()

    def floats(self, where):
        return self._read("f", where)

    def ints(self, where):
        return self._read("i", where)

    def _read(self, code, where):
        values = array.array(code)
        begin = where["offset"]
        end = begin + 4 * where["count"]
        if end > len(self.data):
            fail("scene.bin is shorter than scene.json says")
        values.frombytes(self.data[begin:end])
        return values


def rgba_of(rgb, count):
    """RGB triples as the RGBA Blender's colour attributes hold (alpha 1)."""
    rgba = array.array("f", [1.0]) * (4 * count)
    for channel in range(3):
        rgba[channel::4] = rgb[channel::3]
    return rgba


def clear_scene():
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    for collection in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras, bpy.data.materials, bpy.data.curves):
        for block in list(collection):
            collection.remove(block)


def configure_render(scene, description, output):
    render = description["render"]
    camera = description["camera"]
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = int(render["samples"])
    cycles.seed = int(render["seed"])
    cycles.use_animated_seed = False
    cycles.use_adaptive_sampling = False  # every pixel gets the samples asked for
    cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    cycles.time_limit = float(render["timeLimit"])
    bounces = int(render["maxBounces"])
    cycles.max_bounces = bounces
    cycles.diffuse_bounces = bounces
    cycles.glossy_bounces = bounces
    cycles.transmission_bounces = bounces
    cycles.volume_bounces = 0
    cycles.transparent_max_bounces = 1024  # opacity is not scattering: never cut it short
    # A reference has no bias traded for noise: no clamping, no glossy
    # blur, caustics kept, no light skipped below a threshold.
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = True
    cycles.caustics_refractive = True
    cycles.light_sampling_threshold = 0.0
    # A box filter one pixel wide: each pixel is the mean over its area, as
    # hdHair's coverage and supersampling resolve are.
    cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.cycles_curves.shape = "THICK"
    scene.render.film_transparent = True
    scene.render.resolution_x = int(camera["width"])
    scene.render.resolution_y = int(camera["height"])
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = 1.0
    scene.render.pixel_aspect_y = 1.0
    threads = int(render["threads"])
    scene.render.threads_mode = "FIXED" if threads > 0 else "AUTO"
    if threads > 0:
        scene.render.threads = threads
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGBA"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    scene.render.use_file_extension = False
    scene.render.filepath = output


def add_camera(scene, description):
    camera = description["camera"]
    data = bpy.data.cameras.new("hdhair_camera")
    data.sensor_fit = "HORIZONTAL"
    if camera["type"] == "ORTHO":
        data.type = "ORTHO"
        data.ortho_scale = camera["orthoScale"]
    else:
        data.type = "PERSP"
        data.lens_unit = "FOV"
        data.angle_x = camera["angleX"]
    data.shift_x = camera["shiftX"]
    data.shift_y = camera["shiftY"]
    data.clip_start = camera["clipStart"]
    data.clip_end = camera["clipEnd"]
    obj = bpy.data.objects.new("hdhair_camera", data)
    obj.matrix_world = Matrix(camera["cameraToWorld"])
    scene.collection.objects.link(obj)
    scene.camera = obj


def node_tree(material):
    material.use_nodes = True
    tree = material.node_tree
    tree.nodes.clear()
    return tree, tree.nodes.new("ShaderNodeOutputMaterial")


def attribute(tree, name):
    node = tree.nodes.new("ShaderNodeAttribute")
    node.attribute_name = name
    return node


def opacity_factor(tree, cell):
    """1 where a ray's hit is opaque, 0 where it passes: white noise on the
    hit's position in cells of `cell` units, below the key's opacity. A
    fractional Mix factor would be the obvious way, but with Principled Hair
    Cycles 3.4 then reports too much alpha (0.647 for a factor of 0.5, where
    Emission and Diffuse give 0.5: docs/cycles-reference.md); a factor of 0
    or 1 per hit gives the right alpha and the same colour. The cells are far
    finer than a strand, so every pixel averages over many of them."""
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    scale = tree.nodes.new("ShaderNodeVectorMath")
    scale.operation = "SCALE"
    scale.inputs["Scale"].default_value = 1.0 / cell
    tree.links.new(geometry.outputs["Position"], scale.inputs[0])
    noise = tree.nodes.new("ShaderNodeTexWhiteNoise")
    noise.noise_dimensions = "3D"
    tree.links.new(scale.outputs[0], noise.inputs["Vector"])
    below = tree.nodes.new("ShaderNodeMath")
    below.operation = "LESS_THAN"
    tree.links.new(noise.outputs["Value"], below.inputs[0])
    tree.links.new(attribute(tree, "hdhair_opacity").outputs["Fac"], below.inputs[1])
    return below.outputs[0]


def hair_material(name, prim, cell):
    """Emission (flat) or Principled Hair, or transparency where the opacity
    says (opacity_factor)."""
    material = bpy.data.materials.new(name)
    tree, output = node_tree(material)
    links = tree.links
    if prim["flat"]:
        surface = tree.nodes.new("ShaderNodeEmission")
        surface.inputs["Strength"].default_value = 1.0
        links.new(attribute(tree, "hdhair_color").outputs["Color"], surface.inputs["Color"])
    else:
        hair = prim["hair"]
        surface = tree.nodes.new("ShaderNodeBsdfHairPrincipled")
        surface.parametrization = "ABSORPTION"
        absorption = hair["absorption"]
        surface.inputs["Absorption Coefficient"].default_value = (absorption[0], absorption[1], absorption[2])
        if hair["absorptionPerKey"]:
            links.new(attribute(tree, "hdhair_absorption").outputs["Color"], surface.inputs["Absorption Coefficient"])
        surface.inputs["Roughness"].default_value = hair["roughness"]
        surface.inputs["Radial Roughness"].default_value = hair["radialRoughness"]
        surface.inputs["Coat"].default_value = hair["coat"]
        surface.inputs["IOR"].default_value = hair["ior"]
        surface.inputs["Offset"].default_value = hair["offset"]
        surface.inputs["Random Color"].default_value = 0.0
        surface.inputs["Random Roughness"].default_value = 0.0
    transparent = tree.nodes.new("ShaderNodeBsdfTransparent")
    mix = tree.nodes.new("ShaderNodeMixShader")
    links.new(opacity_factor(tree, cell), mix.inputs["Fac"])
    links.new(transparent.outputs[0], mix.inputs[1])
    links.new(surface.outputs[0], mix.inputs[2])
    links.new(mix.outputs[0], output.inputs["Surface"])
    return material


def add_curves(scene, blob, index, prim):
    """One Curves object: legacy poly splines converted (Blender 3.4 cannot
    add curves to a Curves datablock from Python), then filled in bulk."""
    keys_per_curve = blob.ints(prim["keysPerCurve"])
    name = "hdhair_curves_%d" % index
    legacy = bpy.data.curves.new(name, "CURVE")
    legacy.dimensions = "3D"
    for keys in keys_per_curve:
        spline = legacy.splines.new("POLY")
        spline.points.add(keys - 1)
    obj = bpy.data.objects.new(name, legacy)
    scene.collection.objects.link(obj)
    for other in scene.objects:
        other.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.convert(target="CURVES")
    obj = bpy.context.view_layer.objects.active
    curves = obj.data
    if len(curves.points) != prim["keyCount"]:
        fail("%s: Blender made %d keys, not %d" % (prim["path"], len(curves.points), prim["keyCount"]))
    curves.position_data.foreach_set("vector", blob.floats(prim["positions"]))
    curves.attributes["radius"].data.foreach_set("value", blob.floats(prim["radii"]))
    curves.attributes.new("hdhair_color", "FLOAT_COLOR", "POINT").data.foreach_set(
        "color", rgba_of(blob.floats(prim["colors"]), prim["keyCount"]))
    curves.attributes.new("hdhair_opacity", "FLOAT", "POINT").data.foreach_set(
        "value", blob.floats(prim["opacities"]))
    if not prim["flat"] and prim["hair"]["absorptionPerKey"]:
        # As a colour attribute: Cycles 3.4 renders curves' FLOAT_VECTOR
        # point attributes as zero, their colour attributes as authored.
        curves.attributes.new("hdhair_absorption", "FLOAT_COLOR", "POINT").data.foreach_set(
            "color", rgba_of(blob.floats(prim["absorption"]), prim["keyCount"]))
    radii = blob.floats(prim["radii"])
    mean_width = 2.0 * sum(radii) / max(len(radii), 1)
    curves.materials.append(hair_material(name, prim, max(mean_width, 1e-9) / 16.0))


def add_mesh(scene, blob, index, prim):
    positions = blob.floats(prim["positions"])
    triangles = prim["triangleCount"]
    name = "hdhair_mesh_%d" % index
    mesh = bpy.data.meshes.new(name)
    vertices = [tuple(positions[3 * k:3 * k + 3]) for k in range(3 * triangles)]
    faces = [(3 * t, 3 * t + 1, 3 * t + 2) for t in range(triangles)]
    mesh.from_pydata(vertices, [], faces)
    mesh.attributes.new("hdhair_color", "FLOAT_COLOR", "CORNER").data.foreach_set(
        "color", rgba_of(blob.floats(prim["colors"]), 3 * triangles))
    # hdHair shades the refined surface with its limit normals, per corner.
    normals = blob.floats(prim["normals"])
    mesh.use_auto_smooth = True
    mesh.normals_split_custom_set([tuple(normals[3 * k:3 * k + 3]) for k in range(3 * triangles)])
    for polygon in mesh.polygons:
        polygon.use_smooth = True
    material = bpy.data.materials.new(name)
    tree, output = node_tree(material)
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert, as hdHair's meshes
    tree.links.new(attribute(tree, "hdhair_color").outputs["Color"], diffuse.inputs["Color"])
    tree.links.new(diffuse.outputs[0], output.inputs["Surface"])
    mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)


def split_strength(rgb):
    """Blender lights take one strength and a colour."""
    peak = max(rgb)
    if peak <= 0.0:
        return 0.0, (1.0, 1.0, 1.0)
    return peak, tuple(c / peak for c in rgb)


def add_light(scene, index, light):
    kind = light["kind"]
    data = bpy.data.lights.new("hdhair_light_%d" % index, {"sun": "SUN", "point": "POINT", "spot": "SPOT",
                                                           "area": "AREA"}[kind])
    data.energy, data.color = split_strength(light["strength"])
    if kind == "sun":
        data.angle = light["angle"]
    elif kind in ("point", "spot"):
        data.shadow_soft_size = light["radius"]
        if kind == "spot":
            data.spot_size = max(light["spotSize"], 1e-3)
            data.spot_blend = light["spotBlend"]
    else:
        data.shape = "DISK" if light["disk"] else "RECTANGLE"
        data.size = max(light["sizeX"], 1e-6)
        data.size_y = max(light["sizeY"], 1e-6)
    data.cycles.cast_shadow = bool(light["castShadow"])
    obj = bpy.data.objects.new("hdhair_light_%d" % index, data)
    obj.matrix_world = Matrix(light["lightToWorld"])
    scene.collection.objects.link(obj)


def add_world(scene, domes):
    """Domes as the world: radiance times the latlong texture, looked up along
    the direction hdHair's LatlongDirections gives (the rows in scene.json)."""
    world = bpy.data.worlds.new("hdhair_world")
    scene.world = world
    world.use_nodes = True
    tree = world.node_tree
    tree.nodes.clear()
    output = tree.nodes.new("ShaderNodeOutputWorld")
    shader = None
    for dome in domes:
        background = tree.nodes.new("ShaderNodeBackground")
        strength, color = split_strength(dome["radiance"])
        background.inputs["Strength"].default_value = strength
        background.inputs["Color"].default_value = color + (1.0,)
        if dome["texture"]:
            if not os.path.isfile(dome["texture"]):
                fail("%s: texture '%s' is missing" % (dome["path"], dome["texture"]))
            texture = tree.nodes.new("ShaderNodeTexEnvironment")
            texture.image = bpy.data.images.load(dome["texture"], check_existing=True)
            texture.projection = "EQUIRECTANGULAR"
            coordinates = tree.nodes.new("ShaderNodeTexCoord")
            combine = tree.nodes.new("ShaderNodeCombineXYZ")
            for axis, row in enumerate(dome["worldToTexture"]):
                dot = tree.nodes.new("ShaderNodeVectorMath")
                dot.operation = "DOT_PRODUCT"
                tree.links.new(coordinates.outputs["Generated"], dot.inputs[0])
                dot.inputs[1].default_value = row
                tree.links.new(dot.outputs["Value"], combine.inputs[axis])
            tree.links.new(combine.outputs[0], texture.inputs["Vector"])
            tint = tree.nodes.new("ShaderNodeMixRGB")
            tint.blend_type = "MULTIPLY"
            tint.use_clamp = False
            tint.inputs["Fac"].default_value = 1.0
            tree.links.new(texture.outputs["Color"], tint.inputs["Color1"])
            tint.inputs["Color2"].default_value = color + (1.0,)
            tree.links.new(tint.outputs["Color"], background.inputs["Color"])
        if shader is None:
            shader = background.outputs[0]
        else:
            add = tree.nodes.new("ShaderNodeAddShader")
            tree.links.new(shader, add.inputs[0])
            tree.links.new(background.outputs[0], add.inputs[1])
            shader = add.outputs[0]
    if shader is None:
        background = tree.nodes.new("ShaderNodeBackground")
        background.inputs["Strength"].default_value = 0.0
        shader = background.outputs[0]
    tree.links.new(shader, output.inputs["Surface"])


def main():
    arguments = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(arguments) != 2:
        fail("usage: blender -b --factory-startup -P renderCyclesScene.py -- scene.json out.exr")
    scene_json, output = arguments
    with open(scene_json) as f:
        description = json.load(f)
    if description.get("format") != "hdhair-cycles-scene" or description.get("version") != 1:
        fail("%s is not an hdHair Cycles scene of version 1" % scene_json)
    blob = Blob(os.path.join(os.path.dirname(scene_json), "scene.bin"))
    clear_scene()
    scene = bpy.context.scene
    configure_render(scene, description, output)
    add_camera(scene, description)
    for index, prim in enumerate(description["curves"]):
        add_curves(scene, blob, index, prim)
    for index, prim in enumerate(description["meshes"]):
        add_mesh(scene, blob, index, prim)
    for index, light in enumerate(description["lights"]):
        add_light(scene, index, light)
    add_world(scene, description["domes"])
    start = time.monotonic()
    bpy.ops.render.render(write_still=True)
    if not os.path.isfile(output):
        fail("Cycles wrote no image")
    print("hdhair-cycles: done seconds=%.3f" % (time.monotonic() - start), flush=True)


try:
    main()
except SystemExit:
    raise
except Exception as error:  # every failure becomes the one line hdhair-record reports
    fail("%s: %s" % (type(error).__name__, error))
