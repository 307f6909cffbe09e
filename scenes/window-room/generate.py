#!/usr/bin/env python3
"""Writes window-room.gltf: a closed white room (4 x 3 x 5 m) lit only through a glass window.

The left wall has a 2 x 1.2 m opening filled by a pane of thin-walled glass (KHR_materials_transmission
without a volume: light passes straight through, less what the pane reflects). The interior seen in
archviz scenes: shadow rays cross the pane, and prism samples the sky through it as a portal.
window-room.json adds a constant sky.
Standard library only.
"""

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from gltf_buffer import GltfBuffer, QuadMeshes  # noqa: E402  (scenes/gltf_buffer.py)

X, Y, Z = 4.0, 3.0, 5.0                       # the room spans [0, X] x [0, Y] x [0, Z], +Y up
WINDOW_Y, WINDOW_Z = (1.0, 2.2), (1.5, 3.5)   # the opening in the wall x = 0


def left_wall_quad(y0, y1, z0, z1):
    """A rectangle of the wall x = 0, counter-clockwise seen from inside the room (+x)."""
    return [(0.0, y0, z0), (0.0, y1, z0), (0.0, y1, z1), (0.0, y0, z1)]


def build():
    buffer = GltfBuffer()
    mesh_list = QuadMeshes(buffer)
    add_mesh, nodes = mesh_list.add, mesh_list.nodes

    # Every face counter-clockwise seen from inside, so front faces look into the room.
    floor = [(0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0)]
    ceiling = [(0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z)]
    back = [(0, 0, Z), (0, Y, Z), (X, Y, Z), (X, 0, Z)]
    front = [(0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0)]
    right = [(X, 0, 0), (X, 0, Z), (X, Y, Z), (X, Y, 0)]
    (y0, y1), (z0, z1) = WINDOW_Y, WINDOW_Z
    left = [left_wall_quad(0, y0, 0, Z), left_wall_quad(y1, Y, 0, Z),
            left_wall_quad(y0, y1, 0, z0), left_wall_quad(y0, y1, z1, Z)]
    add_mesh("walls", [floor, ceiling, back, front, right] + left, 0)
    add_mesh("window", [left_wall_quad(y0, y1, z0, z1)], 1)
    # Near the front right corner, turned 135 degrees about +Y: looking at the window wall and the back.
    nodes.append({"name": "camera", "camera": 0, "translation": [3.6, 1.6, 0.4],
                  "rotation": [0.0, 0.9238795, 0.0, 0.3826834]})

    materials = [
        # IOR 1 removes glTF's specular layer: plain Lambertian walls.
        {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0,
                                                    "roughnessFactor": 1.0},
         "extensions": {"KHR_materials_ior": {"ior": 1.0}}},
        {"name": "window_glass", "doubleSided": True,
         "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0,
                                  "roughnessFactor": 0.0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                        "KHR_materials_ior": {"ior": 1.5}}},
    ]
    return {
        "asset": {"version": "2.0", "generator": "prism scenes/window-room/generate.py"},
        "extensionsUsed": ["KHR_materials_ior", "KHR_materials_transmission"],
        "scene": 0,
        "scenes": [{"name": "window-room", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": mesh_list.meshes,
        "materials": materials,
        "cameras": [{"name": "camera", "type": "perspective",
                     "perspective": {"yfov": 1.0, "aspectRatio": 1.0, "znear": 0.01}}],
        "accessors": mesh_list.accessors,
        "bufferViews": buffer.views,
        "buffers": [buffer.embedded()],
    }


def main():
    out = Path(__file__).parent / "window-room.gltf"
    out.write_text(json.dumps(build(), indent=1) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
