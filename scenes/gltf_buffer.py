"""What the scene generators share: one glTF buffer filled view by view, and meshes of quads in it.
Standard library only."""

import base64
import json
import struct


def write_glb(path, gltf, data):
    """Writes gltf (a dict whose buffer 0 has no uri) and the bytes of buffer 0 as a binary glTF."""
    json_bytes = json.dumps(gltf, separators=(",", ":")).encode()
    json_bytes += b" " * (-len(json_bytes) % 4)
    blob = bytes(data) + b"\0" * (-len(data) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(json_bytes) + 8 + len(blob)))
        f.write(struct.pack("<II", len(json_bytes), 0x4E4F534A) + json_bytes)
        f.write(struct.pack("<II", len(blob), 0x004E4942) + blob)


class GltfBuffer:
    """The bytes of buffer 0 and the bufferViews into it."""

    def __init__(self):
        self.data = bytearray()
        self.views = []

    def add_view(self, data, target):
        """Appends data as a new bufferView, 4-byte aligned as accessors need (target 34962 for
        vertex attributes, 34963 for indices, None for an image); returns the view's index."""
        while len(self.data) % 4:
            self.data.append(0)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.views.append(view)
        self.data.extend(data)
        return len(self.views) - 1

    def embedded(self):
        """The glTF "buffers" entry holding the bytes as a data URI."""
        return {"byteLength": len(self.data),
                "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.data)).decode()}


class QuadMeshes:
    """Meshes of quads, one primitive each, with their accessors and the nodes that place them."""

    def __init__(self, buffer):
        self.buffer = buffer
        self.accessors, self.meshes, self.nodes = [], [], []

    def add(self, name, quads, material):
        """A mesh of the quads (corners in order, two triangles each: 0 1 2 and 0 2 3, 16-bit
        indices) with `material`, and a node placing it as it is."""
        positions, indices = [], []
        for quad in quads:
            base = len(positions)
            positions.extend(quad)
            indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
        pos_view = self.buffer.add_view(b"".join(struct.pack("<3f", *p) for p in positions), 34962)
        idx_view = self.buffer.add_view(b"".join(struct.pack("<H", i) for i in indices), 34963)
        self.accessors.append({"bufferView": pos_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                               "min": [min(p[i] for p in positions) for i in range(3)],
                               "max": [max(p[i] for p in positions) for i in range(3)]})
        self.accessors.append({"bufferView": idx_view, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        self.meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(self.accessors) - 2},
                                                          "indices": len(self.accessors) - 1, "material": material}]})
        self.nodes.append({"name": name, "mesh": len(self.meshes) - 1})
