#!/usr/bin/env python3
"""Writes heavy-mesh.glb, prism's benchmark scene for BVH build and traversal at scale: a bumpy
blob of about 1.2 million triangles (a UV sphere displaced by a sum of sines) on a floor, lit by a
rectangular area light, seen by one perspective camera. Standard library only; the output (~45 MB)
is not kept in git: run this script (scripts/bench does) to create it.

Usage: generate.py [--segments N] [OUTPUT]   (N longitudes; N/2 latitudes; 2 N (N/2 - 1) triangles)"""
import argparse
import math
import sys
from array import array
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from gltf_buffer import GltfBuffer, write_glb  # noqa: E402  (scenes/gltf_buffer.py)


def blob(segments):
    """Positions, normals and indices of the displaced sphere (radius ~1, centred at y = 1.1)."""
    rings = segments // 2
    pos, nrm, idx = array("f"), array("f"), array("I")

    def radius(theta, phi):
        return 1.0 + 0.06 * math.sin(9 * theta) * math.sin(7 * phi) + 0.025 * math.sin(31 * theta + 3 * phi)

    def point(theta, phi):
        r = radius(theta, phi)
        st = math.sin(theta)
        return (r * st * math.cos(phi), 1.1 + r * math.cos(theta), r * st * math.sin(phi))

    eps = 1e-4
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            p = point(theta, phi)
            pos.extend(p)
            # The normal from finite differences of the surface along theta and phi (poles: radial).
            t0, t1 = max(theta - eps, 1e-6), min(theta + eps, math.pi - 1e-6)
            a, b = point(t1, phi), point(t0, phi)
            c, d = point(theta, phi + eps), point(theta, phi - eps)
            u = (a[0] - b[0], a[1] - b[1], a[2] - b[2])
            v = (c[0] - d[0], c[1] - d[1], c[2] - d[2])
            n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
            length = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
            if length < 1e-12 or i == 0 or i == rings:
                n = (p[0], p[1] - 1.1, p[2])
                length = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)
            # Outward: the finite-difference cross product may point either way; align with radial.
            sign = 1.0 if n[0] * p[0] + n[1] * (p[1] - 1.1) + n[2] * p[2] >= 0 else -1.0
            nrm.extend((sign * n[0] / length, sign * n[1] / length, sign * n[2] / length))
    for i in range(rings):
        for j in range(segments):
            a = i * segments + j
            b = i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            if i > 0:
                idx.extend((a, b, c))  # counter-clockwise seen from outside
            if i < rings - 1:
                idx.extend((b, d, c))
    return pos, nrm, idx


def quad(corners, normal):
    pos = array("f", [x for c in corners for x in c])
    nrm = array("f", list(normal) * 4)
    return pos, nrm, array("I", [0, 1, 2, 0, 2, 3])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--segments", type=int, default=1100)
    parser.add_argument("output", nargs="?", default=str(Path(__file__).with_name("heavy-mesh.glb")))
    args = parser.parse_args()

    meshes = [
        ("blob", blob(args.segments), 0),
        ("floor", quad([(-4, 0, -4), (-4, 0, 4), (4, 0, 4), (4, 0, -4)], (0, 1, 0)), 1),
        ("light", quad([(-0.8, 3.5, -0.5), (0.8, 3.5, -0.5), (0.8, 3.5, 0.5), (-0.8, 3.5, 0.5)], (0, -1, 0)), 2),
    ]
    buffer = GltfBuffer()
    blob_bytes = buffer.data
    gltf = {
        "asset": {"version": "2.0", "generator": "prism scenes/heavy-mesh/generate.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(meshes) + 1))}],
        "nodes": [],
        "meshes": [],
        "materials": [
            {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.4, 1], "metallicFactor": 0,
                                                       "roughnessFactor": 1}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0,
                                                        "roughnessFactor": 1}},
            {"name": "light", "emissiveFactor": [1, 1, 1],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 12}},
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}},
        ],
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "accessors": [],
        "bufferViews": buffer.views,
        "buffers": [],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.0, "znear": 0.05}}],
    }

    add_view = buffer.add_view

    triangles = 0
    for name, (pos, nrm, idx), material in meshes:
        xs, ys, zs = pos[0::3], pos[1::3], pos[2::3]
        accessors = gltf["accessors"]
        accessors.append({"bufferView": add_view(pos.tobytes(), 34962), "componentType": 5126, "count": len(pos) // 3,
                          "type": "VEC3", "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]})
        accessors.append({"bufferView": add_view(nrm.tobytes(), 34962), "componentType": 5126, "count": len(nrm) // 3,
                          "type": "VEC3"})
        accessors.append({"bufferView": add_view(idx.tobytes(), 34963), "componentType": 5125, "count": len(idx),
                          "type": "SCALAR"})
        a = len(accessors) - 3
        gltf["meshes"].append({"name": name, "primitives": [
            {"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": material}]})
        gltf["nodes"].append({"name": name, "mesh": len(gltf["meshes"]) - 1})
        triangles += len(idx) // 3
    # Camera at (0, 1.6, 5.2) looking at (0, 1.0, 0): a rotation about x by atan(0.6 / 5.2).
    angle = -math.atan2(0.6, 5.2)
    gltf["nodes"].append({"name": "camera", "camera": 0, "translation": [0, 1.6, 5.2],
                          "rotation": [math.sin(angle / 2), 0, 0, math.cos(angle / 2)]})
    gltf["buffers"].append({"byteLength": len(blob_bytes)})

    write_glb(args.output, gltf, blob_bytes)
    print(f"{args.output}: {triangles} triangles")


if __name__ == "__main__":
    main()
