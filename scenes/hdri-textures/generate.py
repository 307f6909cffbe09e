#!/usr/bin/env python3
"""Writes hdri-textures.glb and sky.hdr, prism's benchmark scene for what most production glTF
scenes are: textured materials lit by an HDRI. A paved yard (2048^2 base colour and
metallic-roughness textures, repeated every 3 m), wooden crates (1024^2 base colour and normal map)
and a rough gold block, under a 2048x1024 Radiance HDR sky whose sun, 15000 times brighter than
the zenith, gives about two thirds of the light. hdri-textures.json (kept in git) renders them.
Standard library only; the outputs (~20 MB) are not kept in git: run this script (scripts/bench
does) to create them.

Usage: generate.py [--texture N] [--sky W] [OUTPUT_DIR]   (N: the yard's texture size, the crates'
is N/2; W: the sky's width, its height W/2)"""
import argparse
import math
import random
import struct
import sys
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from gltf_buffer import GltfBuffer, write_glb  # noqa: E402  (scenes/gltf_buffer.py)


def png(width, rows):
    """An 8-bit RGB PNG of the rows (bytes, 3 x width each), unfiltered."""
    rows = list(rows)

    def chunk(tag, data):
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    raw = b"".join(b"\0" + r for r in rows)
    header = struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")


def shifted(row, offset):
    """row with every byte moved by offset, clamped to 0..255 (bytes.translate: C speed)."""
    return row.translate(bytes(min(255, max(0, v + offset)) for v in range(256)))


def paving(n, rng):
    """The yard's base colour and metallic-roughness (G roughness, B metalness 0) textures: 8 x 8
    stone tiles with grout, each tile its own tone, with grain that varies along rows and columns."""
    tile, grout = n // 8, max(2, n // 256)
    tones = [[rng.uniform(0.75, 1.15) for _ in range(8)] for _ in range(8)]
    column_grain = [rng.randint(-14, 14) for _ in range(n)]
    colour_rows, rough_rows = [], []
    grout_colour = bytes([70, 68, 64]) * n
    grout_rough = bytes([255, 242, 0]) * n
    for band in range(8):
        base, rough = bytearray(), bytearray()
        for x in range(n):
            if x % tile < grout:
                base += bytes([70, 68, 64])
                rough += bytes([255, 242, 0])
                continue
            t = tones[band][x // tile]
            g = column_grain[x]
            base += bytes(min(255, max(0, int(c * t) + g)) for c in (150, 138, 118))
            rough += bytes([255, min(255, max(0, int(150 * t) + 2 * g)), 0])
        base, rough = bytes(base), bytes(rough)
        for y in range(tile):
            if y < grout:
                colour_rows.append(grout_colour)
                rough_rows.append(grout_rough)
            else:
                offset = rng.randint(-10, 10)
                colour_rows.append(shifted(base, offset))
                rough_rows.append(shifted(rough, offset))
    return png(n, colour_rows), png(n, rough_rows)


def planks(n, rng):
    """The crates' base colour and tangent-space normal map: 8 horizontal planks with grain, and
    bevelled seams (the normal tilts toward +-v over the seam's edges)."""
    plank, bevel = n // 8, max(2, n // 64)
    colour_rows, normal_rows = [], []
    for p in range(8):
        tone = rng.uniform(0.8, 1.1)
        grain = bytes(min(255, max(0, int(c * tone) + int(18 * math.sin(x * 0.07 + p) + rng.randint(-6, 6))))
                      for x in range(n) for c in (156, 108, 62))
        for y in range(plank):
            colour_rows.append(shifted(grain, int(8 * math.sin(y * 0.3 + 2 * p))))
            tilt = 0
            if y < bevel:
                tilt = -90 * (bevel - y) // bevel
            elif y >= plank - bevel:
                tilt = 90 * (y - (plank - bevel) + 1) // bevel
            z = int(127.5 + 127.5 * math.sqrt(max(0.0, 1 - (tilt / 127.5) ** 2)))
            normal_rows.append(bytes([128, 128 + tilt, z]) * n)
    return png(n, colour_rows), png(n, normal_rows)


def rgbe(r, g, b):
    """One Radiance RGBE texel (Ward, Graphics Gems II)."""
    m = max(r, g, b)
    if m < 1e-32:
        return b"\0\0\0\0"
    mantissa, exponent = math.frexp(m)
    s = mantissa * 256.0 / m
    return bytes((int(r * s), int(g * s), int(b * s), exponent + 128))


def sky(width, rng):
    """A Radiance HDR (flat RGBE scanlines) equirectangular sky, row 0 the zenith: blue above,
    white toward the horizon, a dim ground below, bands of brighter cloud across azimuth, and a
    sun of 0.75 degrees' radius at 35 degrees' elevation."""
    height = width // 2
    clouds = [1.0 + 0.35 * max(0.0, math.sin(k * 0.9) * math.sin(k * 0.37 + 1.0)) for k in range(64)]
    sun_elevation, sun_azimuth, sun_radius = math.radians(35), 0.3 * 2 * math.pi, math.radians(0.75)
    sun_dir = (math.cos(sun_elevation) * math.cos(sun_azimuth), math.sin(sun_elevation),
               math.cos(sun_elevation) * math.sin(sun_azimuth))
    rows = []
    for y in range(height):
        elevation = math.pi / 2 - math.pi * (y + 0.5) / height
        if elevation > 0:
            h = math.sin(elevation)
            base = tuple((1 - h) * w + h * z for w, z in zip((1.1, 1.15, 1.2), (0.25, 0.45, 0.9)))
        else:
            base = (0.3 * 0.35, 0.28 * 0.35, 0.25 * 0.35)
        texels = [rgbe(*(c * (clouds[k] if elevation > 0 else 1.0) for c in base)) for k in range(64)]
        row = bytearray(b"".join(texels[x * 64 // width] for x in range(width)))
        if abs(elevation - sun_elevation) < 2 * sun_radius:
            for x in range(width):
                azimuth = 2 * math.pi * (x + 0.5) / width
                d = (math.cos(elevation) * math.cos(azimuth), math.sin(elevation), math.cos(elevation) * math.sin(azimuth))
                if sum(a * b for a, b in zip(d, sun_dir)) > math.cos(sun_radius):
                    row[4 * x:4 * x + 4] = rgbe(15000.0, 14000.0, 12500.0)
        # A flat scanline must not open as a run-length one does (2, 2, width's high byte < 128).
        assert not (row[0] == 2 and row[1] == 2 and row[2] < 128)
        rows.append(bytes(row))
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode()
    return header + b"".join(rows)


def box(x0, z0, size, height):
    """Five faces (no bottom) of a box standing on y = 0: (corners, normal) each, corners counter-
    clockwise seen from outside, in uv order (0,1) (1,1) (1,0) (0,0)."""
    x1, z1 = x0 + size, z0 + size
    return [
        ([(x0, 0, z1), (x1, 0, z1), (x1, height, z1), (x0, height, z1)], (0, 0, 1)),
        ([(x1, 0, z0), (x0, 0, z0), (x0, height, z0), (x1, height, z0)], (0, 0, -1)),
        ([(x1, 0, z1), (x1, 0, z0), (x1, height, z0), (x1, height, z1)], (1, 0, 0)),
        ([(x0, 0, z0), (x0, 0, z1), (x0, height, z1), (x0, height, z0)], (-1, 0, 0)),
        ([(x0, height, z1), (x1, height, z1), (x1, height, z0), (x0, height, z0)], (0, 1, 0)),
    ]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--texture", type=int, default=2048)
    parser.add_argument("--sky", type=int, default=2048)
    parser.add_argument("output", nargs="?", default=str(Path(__file__).parent))
    args = parser.parse_args()
    out = Path(args.output)
    rng = random.Random(7)

    buffer = GltfBuffer()
    images, textures = [], {}
    for name, data in list(zip(("paving", "paving_mr"), paving(args.texture, rng))) + \
            list(zip(("planks", "planks_normal"), planks(args.texture // 2, rng))):
        images.append({"name": name, "mimeType": "image/png", "bufferView": buffer.add_view(data, None)})
        textures[name] = len(images) - 1

    materials = [
        {"name": "paving", "pbrMetallicRoughness": {"baseColorTexture": {"index": textures["paving"]},
                                                     "metallicRoughnessTexture": {"index": textures["paving_mr"]},
                                                     "metallicFactor": 1, "roughnessFactor": 1}},
        {"name": "planks", "normalTexture": {"index": textures["planks_normal"]},
         "pbrMetallicRoughness": {"baseColorTexture": {"index": textures["planks"]}, "metallicFactor": 0,
                                  "roughnessFactor": 0.75}},
        {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1,
                                                   "roughnessFactor": 0.4}},
    ]
    yard = 60.0  # half its width: wide enough that the sky's ground meets it near the horizon
    faces = [("yard", [([(-yard, 0, yard), (yard, 0, yard), (yard, 0, -yard), (-yard, 0, -yard)], (0, 1, 0))], 0,
              2 * yard / 3),  # the texture repeats every 3 m
             ("crate", box(-2.0, -0.6, 1.2, 1.2), 1, 1.0),
             ("crate", box(-0.4, -2.2, 1.6, 1.6), 1, 1.0),
             ("crate", box(-1.5, -2.6, 0.9, 0.9), 1, 1.0),
             ("gold", box(1.2, -0.2, 0.8, 0.8), 2, 1.0)]
    accessors, meshes, nodes = [], [], []
    triangles = 0
    for name, quads, material, repeat in faces:
        pos, nrm, uv, idx = [], [], [], []
        for corners, normal in quads:
            base = len(pos) // 3
            for c, (u, v) in zip(corners, ((0, 1), (1, 1), (1, 0), (0, 0))):
                pos.extend(c)
                nrm.extend(normal)
                uv.extend((u * repeat, v * repeat))
            idx.extend((base, base + 1, base + 2, base, base + 2, base + 3))
        xs, ys, zs = pos[0::3], pos[1::3], pos[2::3]
        accessors.append({"bufferView": buffer.add_view(struct.pack(f"<{len(pos)}f", *pos), 34962),
                          "componentType": 5126, "count": len(pos) // 3, "type": "VEC3",
                          "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]})
        accessors.append({"bufferView": buffer.add_view(struct.pack(f"<{len(nrm)}f", *nrm), 34962),
                          "componentType": 5126, "count": len(nrm) // 3, "type": "VEC3"})
        accessors.append({"bufferView": buffer.add_view(struct.pack(f"<{len(uv)}f", *uv), 34962),
                          "componentType": 5126, "count": len(uv) // 2, "type": "VEC2"})
        accessors.append({"bufferView": buffer.add_view(struct.pack(f"<{len(idx)}H", *idx), 34963),
                          "componentType": 5123, "count": len(idx), "type": "SCALAR"})
        a = len(accessors) - 4
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1, "TEXCOORD_0": a + 2},
                                                     "indices": a + 3, "material": material}]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})
        triangles += len(idx) // 3
    # Camera at (0.4, 1.7, 5.5) looking at (-0.4, 0.5, -1): a yaw, then a pitch down.
    eye, target = (0.4, 1.7, 5.5), (-0.4, 0.5, -1.0)
    d = [t - e for t, e in zip(target, eye)]
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))
    qy = (0, math.sin(yaw / 2), 0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0, 0, math.cos(pitch / 2))
    q = (qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
         qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
         qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
         qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2])
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": list(q)})
    gltf = {
        "asset": {"version": "2.0", "generator": "prism scenes/hdri-textures/generate.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
        "textures": [{"source": i, "sampler": 0} for i in range(len(images))],
        "samplers": [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}],
        "images": images,
        "accessors": accessors,
        "bufferViews": buffer.views,
        "buffers": [{"byteLength": len(buffer.data)}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1.0, "znear": 0.05}}],
    }
    write_glb(out / "hdri-textures.glb", gltf, buffer.data)
    (out / "sky.hdr").write_bytes(sky(args.sky, rng))
    print(f"{out / 'hdri-textures.glb'}: {triangles} triangles, {len(images)} textures; {out / 'sky.hdr'}")


if __name__ == "__main__":
    main()
