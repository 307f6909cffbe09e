"""Render a glTF scene with Blender Cycles (CPU), settings matched to a prism render.

Run inside Blender, headless:

    blender -b --factory-startup --python-exit-code 1 --python cycles_render.py -- \
        --gltf SCENE.gltf --out OUT.exr --res 512x512 --spp 64 --max-depth 8 [--seed 0] \
        [--bsdf principled [--specular auto|importer|zero]] [--env MAP.hdr [--env-rotation DEG]]

What it does, in order:
  1. empties the factory start-up scene (its cube, lamp and camera would otherwise be rendered)
     and gives the world a black background (the default grey world lights the open box);
  2. imports the glTF with Blender's own importer (Debian 12 needs the numpy.bool shim below);
  3. makes the materials mean what the glTF says:
     - by default (--bsdf diffuse) each Principled BSDF becomes a Lambert Diffuse BSDF of the
       same base colour (plus an Emission shader for emitters): glTF's diffuse lobe is Lambert,
       and with KHR_materials_ior = 1 there is no specular layer. With --bsdf principled the
       importer's Principled BSDF stays, with "Specular" set to 0 for ior 1 (the importer only
       sets the IOR socket, which Principled ignores for opaque dielectrics) and left at the
       importer's 0.5 (F0 0.04, glTF's default ior 1.5) otherwise (--specular); its diffuse is
       not Lambert (4-10% brighter on the Cornell box), and Blender 3.4's Principled adds the
       specular lobe on top of an undiminished diffuse (not energy-conserving);
     - emitters of single-sided glTF materials emit from their front face only (Cycles'
       emission is two-sided; --two-sided-emission keeps that);
  4. with --env MAP, replaces the black world by an Environment Texture (equirectangular,
     linear interpolation, colour space Linear) behind a Mapping node that turns it to prism's
     orientation (ORIENTATION below), Background strength 1;
  5. sets Cycles to unbiased, comparable settings: fixed sample count, no adaptive sampling (unless
     --noise asks for it),
     no denoising, no clamping, no glossy blur, no light threshold, 1-pixel box filter,
     bounces matched to prism's --max-depth (see BOUNCES below);
  6. renders once, writes a float EXR, and prints one machine-readable line:
        CYCLES_RESULT render_s=<s> import_s=<s> spp=<n> max_bounces=<n> res=<w>x<h>
     render_s is the wall time of the render call (scene sync + BVH + path tracing + saving);
     run-peers prefers the path-tracing time it reads from Blender's log.

BOUNCES: prism's --max-depth D traces next-event estimation at the first D surface hits, so its
longest path has D+1 segments (D=1 is direct lighting). Cycles' max_bounces B=0 is already
direct lighting, so the same path length is B = D - 1. The per-type limits (diffuse, glossy,
transmission, volume, transparent) are set to B as well so that only the total limit binds.
Checked on the Cornell box (Diffuse BSDF): with B = D - 1 Cycles' mean is within 1.5% of
prism's at D = 1, 2 and 8; with B = D it is 15% brighter at D = 1.
"""

import argparse
import sys
import time

import bpy


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_render.py")
    p.add_argument("--gltf", required=True, help="glTF 2.0 scene to import")
    p.add_argument("--out", required=True, help="output OpenEXR path (float RGBA)")
    p.add_argument("--res", default="512x512", help="WIDTHxHEIGHT")
    p.add_argument("--spp", type=int, default=64, help="samples per pixel (the most, with --noise)")
    p.add_argument("--noise", type=float, default=0.0,
                   help="adaptive sampling's noise threshold (Cycles' own measure); 0 = off, every pixel --spp")
    p.add_argument("--max-depth", type=int, default=8,
                   help="prism-style maximum depth (bounces); Cycles gets max_bounces = this - 1")
    p.add_argument("--seed", type=int, default=0, help="Cycles sampling seed")
    p.add_argument("--threads", type=int, default=0, help="render threads, 0 = all cores")
    p.add_argument("--bsdf", choices=["principled", "diffuse"], default="diffuse",
                   help="a Lambert Diffuse BSDF (glTF's diffuse model, prism's) or the importer's "
                        "Principled BSDF with specular 0")
    p.add_argument("--env", help="equirectangular environment map (linear EXR/HDR) lighting the "
                        "scene like prism --env MAP; default: a black world")
    p.add_argument("--env-strength", type=float, default=1.0, help="Background strength of --env")
    p.add_argument("--env-rotation", type=float, default=ENV_ROTATION_Z,
                   help="rotation of the map about Blender's +Z in degrees (Mapping node); the "
                        "default puts the map where prism puts it (see ORIENTATION)")
    p.add_argument("--specular", choices=["auto", "importer", "zero"], default="auto",
                   help="with --bsdf principled: auto sets Specular to 0 where the glTF's ior is 1 "
                        "and keeps the importer's value elsewhere (glTF's default ior 1.5: 0.5, "
                        "F0 0.04); importer never changes it; zero always sets 0 (diagnosis)")
    p.add_argument("--two-sided-emission", dest="one_sided", action="store_false",
                   help="keep Cycles' two-sided emission (default: front faces only for "
                        "single-sided glTF materials, as glTF has no back face there)")
    return p.parse_args(argv)


# ORIENTATION of --env. prism (core/environment_light.cpp): u = 0.5 + atan2(x, -z) / 2pi in glTF
# axes, so the map's centre faces glTF -Z and u grows toward +X. Blender's importer maps glTF
# (x, y, z) to Blender (x, -z, y), and Cycles' equirectangular lookup is
# u = 0.5 - atan2(y, x) / 2pi in Blender axes (centre toward +X, u growing toward -Y).
# Substituting, Cycles' u = prism's u - 0.25: same handedness (no mirror), a quarter turn apart.
# A Mapping node rotating the lookup direction by -90 degrees about +Z makes them agree.
# Checked empirically, see bench/peers/README.md.
ENV_ROTATION_Z = -90.0


def environment_world(path, strength, rotation_z):
    """A world whose Background is the equirectangular map at path (linear), rotated about +Z."""
    import math
    world = bpy.context.scene.world
    nt = world.node_tree
    for node in list(nt.nodes):
        nt.nodes.remove(node)
    coord = nt.nodes.new("ShaderNodeTexCoord")
    mapping = nt.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(rotation_z))
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.projection = "EQUIRECTANGULAR"
    tex.interpolation = "Linear"
    tex.image = bpy.data.images.load(path, check_existing=True)
    tex.image.colorspace_settings.name = "Linear"  # EXR/HDR are linear already; no view transform
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = strength
    out = nt.nodes.new("ShaderNodeOutputWorld")
    nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
    nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    # Importance-sample the map (Blender 3.4: world "Multiple Importance" on, map resolution
    # automatic); both are Blender's defaults, set here so they do not depend on the start-up file.
    world.cycles.sampling_method = "AUTOMATIC"
    world.cycles.max_bounces = 1024
    print(f"cycles_render: world: {path} x{strength:g}, rotated {rotation_z:g} deg about +Z, "
          f"{tex.image.size[0]}x{tex.image.size[1]}")


def empty_scene():
    """Remove every object of the factory start-up file and make the world black."""
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    world = bpy.data.worlds.new("black") if not bpy.data.worlds else bpy.data.worlds[0]
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    if bg is not None:
        bg.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        bg.inputs["Strength"].default_value = 0.0
    world.color = (0.0, 0.0, 0.0)
    bpy.context.scene.world = world


def import_gltf(path):
    # Debian 12: Blender 3.4's importer uses numpy.bool, which numpy 1.24 removed. Restore the
    # alias in this process only; nothing on disk changes.
    import warnings
    import numpy
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numpy 1.24 warns when asked about numpy.bool
        if not hasattr(numpy, "bool"):
            numpy.bool = bool
    bpy.ops.import_scene.gltf(filepath=path)


def adjust_materials(bsdf_kind, specular="auto"):
    """Make the imported materials match glTF semantics (ior 1 = no specular layer)."""
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        for node in list(nodes):
            if node.type != "BSDF_PRINCIPLED":
                continue
            emission_strength = node.inputs["Emission Strength"].default_value
            emission = tuple(node.inputs["Emission"].default_value)
            if bsdf_kind == "principled":
                if specular == "zero" or (
                        specular == "auto" and abs(node.inputs["IOR"].default_value - 1.0) < 1e-6):
                    node.inputs["Specular"].default_value = 0.0
                print(f"cycles_render: material {mat.name}: principled, specular "
                      f"{node.inputs['Specular'].default_value:g}, ior "
                      f"{node.inputs['IOR'].default_value:g}")
                continue
            # Lambert: Diffuse BSDF (roughness 0) plus, for emitters, an Emission shader.
            out_links = [l for l in links if l.from_node == node]
            diffuse = nodes.new("ShaderNodeBsdfDiffuse")
            diffuse.inputs["Color"].default_value = node.inputs["Base Color"].default_value
            diffuse.inputs["Roughness"].default_value = 0.0
            shader = diffuse
            if emission_strength > 0 and any(c > 0 for c in emission[:3]):
                em = nodes.new("ShaderNodeEmission")
                em.inputs["Color"].default_value = emission
                em.inputs["Strength"].default_value = emission_strength
                add = nodes.new("ShaderNodeAddShader")
                links.new(diffuse.outputs[0], add.inputs[0])
                links.new(em.outputs[0], add.inputs[1])
                shader = add
            for l in out_links:
                links.new(shader.outputs[0], l.to_socket)
            nodes.remove(node)
        print(f"cycles_render: material {mat.name}: {bsdf_kind}")


def one_sided_emission():
    """Emit from front faces only, for materials the glTF marks single-sided.

    Cycles' emission is two-sided and ignores backface culling (viewport-only), whereas a glTF
    material without doubleSided has no back face. For the Cornell box this matters: the light
    quad hangs just below the ceiling and its back would light the ceiling through the gap."""
    for mat in bpy.data.materials:
        if not mat.use_nodes or not mat.use_backface_culling:
            continue
        nodes, links = mat.node_tree.nodes, mat.node_tree.links
        out = next((n for n in nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
        if out is None or not out.inputs["Surface"].is_linked:
            continue
        emits = any(n.type == "EMISSION" or (n.type == "BSDF_PRINCIPLED" and
                    n.inputs["Emission Strength"].default_value > 0 and
                    any(c > 0 for c in n.inputs["Emission"].default_value[:3])) for n in nodes)
        if not emits:
            continue
        link = out.inputs["Surface"].links[0]
        front = link.from_socket
        geometry = nodes.new("ShaderNodeNewGeometry")
        black = nodes.new("ShaderNodeBsdfDiffuse")  # the back: a black, non-emitting surface
        black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        mix = nodes.new("ShaderNodeMixShader")
        links.remove(link)
        links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        links.new(front, mix.inputs[1])
        links.new(black.outputs[0], mix.inputs[2])
        links.new(mix.outputs[0], out.inputs["Surface"])
        print(f"cycles_render: material {mat.name}: emits from its front face only")


def configure(args):
    scene = bpy.context.scene
    width, height = (int(v) for v in args.res.lower().split("x"))
    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if not cameras:
        sys.exit("cycles_render: the glTF has no camera")
    scene.camera = cameras[0]

    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.filter_size = 1.0  # Cycles' pixel filter width in pixels (its default is a 1.5 px Gaussian)
    r.use_persistent_data = False
    r.threads_mode = "FIXED" if args.threads > 0 else "AUTO"
    if args.threads > 0:
        r.threads = args.threads
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGBA"
    r.image_settings.exr_codec = "ZIP"
    scene.view_settings.view_transform = "Standard"  # EXR is written linear anyway
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0

    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.use_adaptive_sampling = args.noise > 0
    if args.noise > 0:
        c.adaptive_threshold = args.noise
        c.adaptive_min_samples = 0  # Cycles' automatic minimum
    c.use_denoising = False
    c.seed = args.seed
    c.use_animated_seed = False
    c.sample_clamp_direct = 0.0  # 0 = no clamping
    c.sample_clamp_indirect = 0.0  # default 10: biased
    c.blur_glossy = 0.0  # "filter glossy", default 1: biased
    c.light_sampling_threshold = 0.0  # default 0.01 skips dim lights: biased
    c.caustics_reflective = True
    c.caustics_refractive = True
    bounces = max(0, args.max_depth - 1)  # see BOUNCES in the module doc
    c.max_bounces = bounces
    c.diffuse_bounces = bounces
    c.glossy_bounces = bounces
    c.transmission_bounces = bounces
    c.volume_bounces = bounces
    c.transparent_max_bounces = bounces
    c.film_exposure = 1.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    r.film_transparent = False
    r.filepath = args.out
    r.use_file_extension = False
    return bounces, width, height


def main():
    args = parse_args()
    t0 = time.perf_counter()
    empty_scene()
    import_gltf(args.gltf)
    adjust_materials(args.bsdf, args.specular)
    if args.one_sided:
        one_sided_emission()
    bounces, width, height = configure(args)
    if args.env:
        environment_world(args.env, args.env_strength, args.env_rotation)
    t1 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    t2 = time.perf_counter()
    print(f"CYCLES_RESULT render_s={t2 - t1:.4f} import_s={t1 - t0:.4f} spp={args.spp} "
          f"max_bounces={bounces} res={width}x{height} "
          f"pattern={bpy.context.scene.cycles.sampling_pattern} out={args.out}", flush=True)


main()
