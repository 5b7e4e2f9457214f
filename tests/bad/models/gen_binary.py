#!/usr/bin/env python3
"""Writes the binary PLY and glTF files of issue 15 (committed; run again
only to change them): python3 tests/bad/models/gen_binary.py
Bad files go to tests/bad/models/, their in-range controls (same bytes but
the defect) to tests/models/."""
import base64, json, os, struct

here = os.path.dirname(os.path.abspath(__file__))
good = os.path.join(here, '..', '..', 'models')
V = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
F = [(0, 1, 2), (2, 1, 3)]


def ply(endian, nv_decl, nf_decl, faces, comment):
    fmt = 'binary_little_endian' if endian == '<' else 'binary_big_endian'
    h = (f"ply\nformat {fmt} 1.0\ncomment shadowlab test: {comment}\n"
         f"element vertex {nv_decl}\nproperty float x\nproperty float y\nproperty float z\n"
         f"element face {nf_decl}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    b = b''.join(struct.pack(endian + '3f', *v) for v in V)
    return h + b + b''.join(struct.pack(endian + 'B3i', 3, *f) for f in faces)


def put(d, name, data):
    with open(os.path.join(d, name), 'wb') as f:
        f.write(data)


put(here, 'short_binary_le.ply', ply('<', 40, 2, F, 'declares 40 vertices, holds 4'))
put(here, 'short_binary_be.ply', ply('>', 4, 5, F, 'declares 5 faces, holds 2'))
put(here, 'bad_index_le.ply', ply('<', 4, 2, [(0, 1, 2), (2, 1, 7)], 'face 1 names vertex 7 of 4'))
put(here, 'bad_index_be.ply', ply('>', 4, 2, [(0, 1, 2), (2, -1, 3)], 'face 1 names vertex -1 of 4'))
put(good, 'quad_le.ply', ply('<', 4, 2, F, 'two triangles, little endian'))
put(good, 'quad_be.ply', ply('>', 4, 2, F, 'two triangles, big endian'))


def gltf(idx, note):
    pos = b''.join(struct.pack('<3f', *v) for v in V)
    ib = struct.pack('<6H', *idx)
    buf = pos + ib
    g = {"asset": {"version": "2.0", "generator": "shadowlab test: " + note},
         "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
         "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
         "buffers": [{"byteLength": len(buf),
                      "uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode()}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                         {"buffer": 0, "byteOffset": len(pos), "byteLength": len(ib)}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                        "min": [0, 0, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
    return (json.dumps(g, indent=1) + "\n").encode()


put(here, 'bad_index.gltf', gltf((0, 1, 2, 2, 1, 9), 'index 9 of 4 vertices'))
put(here, 'bad_index_all.gltf', gltf((0, 1, 9, 9, 1, 3), 'every triangle names vertex 9 of 4'))
put(good, 'quad_index.gltf', gltf((0, 1, 2, 2, 1, 3), 'two triangles, indices in range'))
