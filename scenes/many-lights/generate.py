#!/usr/bin/env python3
"""Writes many-lights.gltf: a hall lit by 64 small lamps, for measuring how next-event estimation
chooses among many lights. An 8 x 8 grid of 12 cm square lamps hangs 1.2 m over a 12 x 12 m floor
under a ceiling, among 7 x 7 pillars that hide most lamps from most of the floor; lamps differ in
colour and in strength (over a factor of 8). Each point of the floor is lit mostly by the few lamps
near it, which choosing lights by power alone cannot know. Lambertian materials only (glTF
dielectrics with KHR_materials_ior `ior: 1`). Standard library only; run it to regenerate."""
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from gltf_buffer import GltfBuffer, QuadMeshes  # noqa: E402  (scenes/gltf_buffer.py)

GRID = 8          # lamps per side
SPACING = 1.5     # metres between lamps
LAMP = 0.12       # lamp side, metres
LAMP_HEIGHT = 1.2
CEILING = 2.6
HALF = GRID * SPACING / 2  # the floor spans [-HALF, HALF] in x and z
PILLAR = 0.25     # pillar side, metres

MATERIALS = {
    "floor": (0.6, 0.6, 0.58),
    "ceiling": (0.3, 0.3, 0.3),
    "pillar": (0.75, 0.72, 0.68),
}
# Lamp colours (peak-normalised) and strengths cycle so that neighbours differ.
LAMP_COLOURS = [(1.0, 0.75, 0.45), (0.55, 0.7, 1.0), (1.0, 0.95, 0.9), (0.9, 0.45, 0.3)]
LAMP_STRENGTHS = [40.0, 120.0, 15.0, 80.0, 25.0]


def quad(c, u, v):
    """Corners c, c + u, c + u + v, c + v: counter-clockwise around cross(u, v)."""
    return [c, tuple(a + b for a, b in zip(c, u)), tuple(a + b + d for a, b, d in zip(c, u, v)),
            tuple(a + d for a, d in zip(c, v))]


def box(lo, hi):
    """The six outward-facing quads of an axis-aligned box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    return [
        quad((x0, y0, z0), (0, dy, 0), (dx, 0, 0)),  # -z
        quad((x0, y0, z1), (dx, 0, 0), (0, dy, 0)),  # +z
        quad((x0, y0, z0), (0, 0, dz), (0, dy, 0)),  # -x
        quad((x1, y0, z0), (0, dy, 0), (0, 0, dz)),  # +x
        quad((x0, y1, z0), (0, 0, dz), (dx, 0, 0)),  # +y
    ]


def look_at_rotation(eye, target):
    """The unit quaternion (x, y, z, w) turning glTF's camera (looking down -Z, +Y up) toward target."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    back = [-c / n for c in f]  # the camera's +Z
    up = (0.0, 1.0, 0.0)
    right = [up[1] * back[2] - up[2] * back[1], up[2] * back[0] - up[0] * back[2], up[0] * back[1] - up[1] * back[0]]
    n = math.sqrt(sum(c * c for c in right))
    right = [c / n for c in right]
    true_up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
               back[0] * right[1] - back[1] * right[0]]
    m = [[right[0], true_up[0], back[0]], [right[1], true_up[1], back[1]], [right[2], true_up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
    q[i] = s / 4
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    return q


def build():
    buffer = GltfBuffer()
    mesh_list = QuadMeshes(buffer)
    add_mesh, nodes = mesh_list.add, mesh_list.nodes
    materials = []

    for name, colour in MATERIALS.items():
        materials.append({"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*colour, 1.0],
                                                                  "metallicFactor": 0.0, "roughnessFactor": 1.0},
                          "extensions": {"KHR_materials_ior": {"ior": 1.0}}})
    lamp_materials = {}
    for c, colour in enumerate(LAMP_COLOURS):
        for s, strength in enumerate(LAMP_STRENGTHS):
            lamp_materials[(c, s)] = len(materials)
            materials.append({"name": f"lamp_{c}_{s}", "emissiveFactor": list(colour),
                              "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0},
                              "extensions": {"KHR_materials_ior": {"ior": 1.0},
                                             "KHR_materials_emissive_strength": {"emissiveStrength": strength}}})

    add_mesh("floor", [quad((-HALF, 0, -HALF), (0, 0, 2 * HALF), (2 * HALF, 0, 0))], 0)
    add_mesh("ceiling", [quad((-HALF, CEILING, -HALF), (2 * HALF, 0, 0), (0, 0, 2 * HALF))], 1)
    pillars = []
    for i in range(GRID - 1):
        for j in range(GRID - 1):
            x = -HALF + (i + 1) * SPACING
            z = -HALF + (j + 1) * SPACING
            pillars.extend(box((x - PILLAR / 2, 0, z - PILLAR / 2), (x + PILLAR / 2, CEILING, z + PILLAR / 2)))
    add_mesh("pillars", pillars, 2)
    for i in range(GRID):
        for j in range(GRID):
            x = -HALF + (i + 0.5) * SPACING - LAMP / 2
            z = -HALF + (j + 0.5) * SPACING - LAMP / 2
            k = i * GRID + j
            material = lamp_materials[(k % len(LAMP_COLOURS), (k * 3 + i) % len(LAMP_STRENGTHS))]
            # Facing down: counter-clockwise seen from below.
            add_mesh(f"lamp_{i}_{j}", [quad((x, LAMP_HEIGHT, z), (LAMP, 0, 0), (0, 0, LAMP))], material)

    eye, target = (-4.6, 0.9, -5.2), (0.8, 0.75, 0.9)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_rotation(eye, target)})
    return {
        "asset": {"version": "2.0", "generator": "prism scenes/many-lights/generate.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_ior"],
        "scene": 0,
        "scenes": [{"name": "many-lights", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": mesh_list.meshes,
        "materials": materials,
        "cameras": [{"name": "camera", "type": "perspective",
                     "perspective": {"yfov": 0.9, "aspectRatio": 1.0, "znear": 0.01}}],
        "accessors": mesh_list.accessors,
        "bufferViews": buffer.views,
        "buffers": [buffer.embedded()],
    }


def main():
    out = Path(__file__).parent / "many-lights.gltf"
    out.write_text(json.dumps(build(), indent=1) + "\n")
    print(f"wrote {out} ({GRID * GRID} lamps, {2 * GRID * GRID} emissive triangles)")


if __name__ == "__main__":
    main()
