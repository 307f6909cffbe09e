#!/usr/bin/env python3
"""Writes cornell-box.gltf: the Cornell box from the measured data published by the Cornell
University Program of Computer Graphics (www.graphics.cornell.edu/online/box/data.html),
converted from millimetres to metres; and ../cornell-glass/cornell-glass.gltf, the same box
with the tall block made of tinted, absorbing glass. Standard library only; run it to
regenerate both files."""
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from gltf_buffer import GltfBuffer, QuadMeshes  # noqa: E402  (scenes/gltf_buffer.py)

MM = 0.001  # the published data is in millimetres

# Linear-RGB reflectances commonly used for the box's measured spectra.
MATERIALS = {
    "white": (0.725, 0.71, 0.68),
    "red": (0.63, 0.065, 0.05),
    "green": (0.14, 0.45, 0.091),
    "light": (0.78, 0.78, 0.78),
}
# The glass variant's tall block: clear glass (IOR 1.5) whose interior absorbs towards teal,
# keeping 45% / 80% / 90% of red / green / blue per 10 cm (KHR_materials_volume).
TINTED_GLASS = {
    "name": "tinted_glass",
    "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
    "extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_ior": {"ior": 1.5},
        "KHR_materials_volume": {"thicknessFactor": 0.16, "attenuationColor": [0.45, 0.8, 0.9], "attenuationDistance": 0.1},
    },
}
LIGHT_RADIANCE = (17.0, 12.0, 4.0)  # W / (sr m^2) per channel

BOX_CENTRE = (278.0, 274.4, 279.6)

# `--large-light OUT` writes a variant whose light covers most of the ceiling (456 x 459 mm) at a
# tenth of the radiance: the walls' tops then lie close to a big emitter, the case where sampling
# a light by solid angle rather than by area pays (docs/PERFORMANCE.md, "Light sampling").
LARGE_LIGHT = [[(506, 548.3, 50), (506, 548.3, 509), (50, 548.3, 509), (50, 548.3, 50)]]
LARGE_LIGHT_SCALE = 0.1

# Each surface: name, material, quads (4 corners each), and where its front faces point:
# "in" = toward the box centre, "out" = away from the object's own centre, or a fixed vector.
SURFACES = [
    ("floor", "white", [[(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]], "in"),
    ("ceiling", "white", [[(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]], "in"),
    ("back_wall", "white", [[(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]], "in"),
    ("right_wall", "green", [[(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]], "in"),
    ("left_wall", "red", [[(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]], "in"),
    ("short_block", "white", [
        [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
        [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
        [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
        [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
        [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)]], "out"),
    ("tall_block", "white", [
        [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
        [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
        [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
        [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
        [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)]], "out"),
    # The light hangs 0.5 mm below the ceiling so the two never share a plane.
    ("light", "light", [[(343, 548.3, 227), (343, 548.3, 332), (213, 548.3, 332), (213, 548.3, 227)]], (0, -1, 0)),
]


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def centre(points):
    return tuple(sum(p[i] for p in points) / len(points) for i in range(3))


def oriented(quad, facing, object_centre):
    """The quad's corners ordered counter-clockwise around the normal it should face."""
    normal = cross(sub(quad[1], quad[0]), sub(quad[2], quad[0]))
    qc = centre(quad)
    if facing == "in":
        want = sub(BOX_CENTRE, qc)
    elif facing == "out":
        want = sub(qc, object_centre)
    else:
        want = facing
    return quad if dot(normal, want) > 0 else list(reversed(quad))


def build(glass, large_light=False):
    buffer = GltfBuffer()
    mesh_list = QuadMeshes(buffer)
    nodes = mesh_list.nodes
    material_index = {name: i for i, name in enumerate(MATERIALS)}

    for name, material, quads, facing in SURFACES:
        if large_light and name == "light":
            quads = LARGE_LIGHT
        corners = [p for q in quads for p in q]
        object_centre = centre(corners)
        in_metres = [[tuple(c * MM for c in p) for p in oriented(quad, facing, object_centre)] for quad in quads]
        index = len(MATERIALS) if glass and name == "tall_block" else material_index[material]
        mesh_list.add(name, in_metres, index)

    # Camera at (278, 273, -800) mm looking down +z: the glTF camera looks down its -Z, so the
    # node turns half a turn about +Y. Film 25 mm behind a 35 mm lens: yfov = 2 atan(12.5 / 35).
    nodes.append({"name": "camera", "camera": 0, "translation": [278 * MM, 273 * MM, -800 * MM],
                  "rotation": [0.0, 1.0, 0.0, 0.0]})

    peak = max(LIGHT_RADIANCE)
    materials = []
    for name, colour in MATERIALS.items():
        # IOR 1 removes glTF's specular layer: the classic box is purely Lambertian.
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*colour, 1.0], "metallicFactor": 0.0,
                                                     "roughnessFactor": 1.0},
             "extensions": {"KHR_materials_ior": {"ior": 1.0}}}
        if name == "light":
            m["emissiveFactor"] = [c / peak for c in LIGHT_RADIANCE]
            strength = peak * (LARGE_LIGHT_SCALE if large_light else 1.0)
            m["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        materials.append(m)
    extensions = ["KHR_materials_emissive_strength", "KHR_materials_ior"]
    if glass:
        materials.append(TINTED_GLASS)
        extensions += ["KHR_materials_transmission", "KHR_materials_volume"]

    return {
        "asset": {"version": "2.0", "generator": "prism scenes/cornell-box/generate.py"},
        "extensionsUsed": extensions,
        "scene": 0,
        "scenes": [{"name": "cornell-glass" if glass else "cornell-box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": mesh_list.meshes,
        "materials": materials,
        "cameras": [{"name": "camera", "type": "perspective",
                     "perspective": {"yfov": 2 * math.atan(12.5 / 35.0), "aspectRatio": 1.0, "znear": 0.01}}],
        "accessors": mesh_list.accessors,
        "bufferViews": buffer.views,
        "buffers": [buffer.embedded()],
    }


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--large-light":
        Path(sys.argv[2]).write_text(json.dumps(build(False, large_light=True), indent=1) + "\n")
        print(f"wrote {sys.argv[2]} (the large-light variant)")
        return
    here = Path(__file__).parent
    for glass, out in ((False, here / "cornell-box.gltf"), (True, here.parent / "cornell-glass" / "cornell-glass.gltf")):
        out.write_text(json.dumps(build(glass), indent=1) + "\n")
        print(f"wrote {out} ({sum(len(s[2]) * 2 for s in SURFACES)} triangles)")


if __name__ == "__main__":
    main()
