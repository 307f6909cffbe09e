#!/usr/bin/env python3
"""Writes the deliberately broken glTF files of tests/broken/ (each breaks one rule).
Run from anywhere: python3 tests/broken/make_broken.py. The files are committed; this records
how they were made."""
import base64, copy, json, os, struct

HERE = os.path.dirname(os.path.abspath(__file__))

positions = struct.pack('<9f', 0, 0, 0, 1, 0, 0, 0, 1, 0)
indices = struct.pack('<3H', 0, 1, 2) + b'\0\0'
blob = positions + indices
uri = 'data:application/octet-stream;base64,' + base64.b64encode(blob).decode()

base = {
    'asset': {'version': '2.0'},
    'scene': 0,
    'scenes': [{'nodes': [0]}],
    'nodes': [{'mesh': 0}],
    'meshes': [{'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1}]}],
    'accessors': [
        {'bufferView': 0, 'componentType': 5126, 'count': 3, 'type': 'VEC3'},
        {'bufferView': 1, 'componentType': 5123, 'count': 3, 'type': 'SCALAR'},
    ],
    'bufferViews': [
        {'buffer': 0, 'byteOffset': 0, 'byteLength': 36},
        {'buffer': 0, 'byteOffset': 36, 'byteLength': 6},
    ],
    'buffers': [{'byteLength': len(blob), 'uri': uri}],
}


def variant(name, edit, text_edit=lambda text: text):
    doc = copy.deepcopy(base)
    edit(doc)
    with open(os.path.join(HERE, name), 'w') as f:
        f.write(text_edit(json.dumps(doc, indent=1)))


def glb(name, json_bytes, bin_bytes, version=2, json_length=None):
    json_bytes += b' ' * (-len(json_bytes) % 4)
    chunks = struct.pack('<II', json_length if json_length is not None else len(json_bytes), 0x4E4F534A) + json_bytes
    if bin_bytes is not None:
        chunks += struct.pack('<II', len(bin_bytes), 0x004E4942) + bin_bytes
    with open(os.path.join(HERE, name), 'wb') as f:
        f.write(b'glTF' + struct.pack('<II', version, 12 + len(chunks)) + chunks)


def set_path(path, value):
    def edit(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return edit


# A valid triangle, the seed the others break.
variant('triangle.gltf', lambda d: None)
# 2^30 vertices declared over a 36-byte view: refused before allocating 24 GiB.
variant('absurd-count.gltf', set_path(['accessors', 0, 'count'], 1 << 30))
# 2^40 vertices: beyond any count prism accepts.
variant('absurd-count-2-40.gltf', set_path(['accessors', 0, 'count'], 1 << 40))
# 2^28 vertices with no bufferView (zeros by the spec): the memory estimate refuses it.
variant('absurd-count-no-view.gltf', lambda d: (d['accessors'][0].pop('bufferView'),
                                                 d['accessors'][0].__setitem__('count', 1 << 28)))
# A bufferView that runs past the end of its buffer.
variant('view-past-buffer.gltf', set_path(['bufferViews', 0, 'byteLength'], 4096))
# An accessor whose byteOffset puts its last element past its view.
variant('accessor-past-view.gltf', set_path(['accessors', 0, 'byteOffset'], 8))
# An image stored in a bufferView that runs past the buffer.
variant('image-view-past-buffer.gltf', lambda d: (
    d['bufferViews'].append({'buffer': 0, 'byteOffset': 40, 'byteLength': 1 << 20}),
    d.__setitem__('images', [{'bufferView': 2, 'mimeType': 'image/png'}]),
    d.__setitem__('textures', [{'source': 0}]),
    d.__setitem__('materials', [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}}}]),
    d['meshes'][0]['primitives'][0].__setitem__('material', 0)))
# An image stored in a bufferView whose bytes are not an image.
variant('image-not-decodable.gltf', lambda d: (
    d.__setitem__('images', [{'bufferView': 0, 'mimeType': 'image/png'}]),
    d.__setitem__('textures', [{'source': 0}]),
    d.__setitem__('materials', [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}}}]),
    d['meshes'][0]['primitives'][0].__setitem__('material', 0)))
# A texture whose image file does not exist.
variant('image-missing-file.gltf', lambda d: (
    d.__setitem__('images', [{'uri': 'no-such-texture.png'}]),
    d.__setitem__('textures', [{'source': 0}]),
    d.__setitem__('materials', [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}}}]),
    d['meshes'][0]['primitives'][0].__setitem__('material', 0)))
# POSITION as unsigned bytes: the spec allows only FLOAT.
variant('position-wrong-component-type.gltf', set_path(['accessors', 0, 'componentType'], 5121))
# POSITION as VEC2.
variant('position-wrong-type.gltf', set_path(['accessors', 0, 'type'], 'VEC2'))
# An index that points past the vertices.
variant('index-past-vertices.gltf', set_path(['accessors', 0, 'count'], 2))
# A mesh index out of range.
variant('mesh-out-of-range.gltf', set_path(['nodes', 0, 'mesh'], 7))
# A node that is its own child.
variant('node-cycle.gltf', set_path(['nodes', 0, 'children'], [0]))
# A translation of 1e999 (infinity once parsed).
variant('translation-infinite.gltf', set_path(['nodes', 0, 'translation'], ['INF', 0, 0]),
        lambda text: text.replace('"INF"', '1e999'))
# An extension prism does not implement, declared required.
variant('required-extension.gltf', lambda d: d.__setitem__('extensionsRequired', ['KHR_mesh_quantization']))
# Points: skipped with a warning, nothing else to render.
variant('points-only.gltf', set_path(['meshes', 0, 'primitives', 0, 'mode'], 0))
# A JSON syntax error.
with open(os.path.join(HERE, 'not-json.gltf'), 'w') as f:
    f.write('{"asset": {"version": "2.0"}, "scenes": [}\n')

# GLB: a valid one, a wrong version, a JSON chunk longer than the file, a file cut short.
glb_doc = copy.deepcopy(base)
glb_doc['buffers'] = [{'byteLength': len(blob)}]
glb_json = json.dumps(glb_doc).encode()
glb('triangle.glb', glb_json, blob)
glb('glb-version-1.glb', glb_json, blob, version=1)
glb('glb-json-past-end.glb', glb_json, blob, json_length=1 << 20)
glb_short = copy.deepcopy(glb_doc)
glb_short['buffers'][0]['byteLength'] = 4096
glb('glb-bin-too-short.glb', json.dumps(glb_short).encode(), blob)
