#!/usr/bin/env python3
"""Writes tests/data/scene_mixed.gltf, the mixed scene of docs/scene.md and tests/test_scene.cpp:
an opaque floor, a grey translucent sphere, a coloured translucent sphere and a bending marble
bar (metres, as glTF). Deterministic; rerun after editing and commit the output:

    python3 tests/data/make_scene_data.py
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, UINT = 5126, 5125


def sphere(r, rings, segs, centre):
    pos, idx = [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segs + 1):
            ph = 2 * math.pi * j / segs
            pos.append((centre[0] + r * math.sin(th) * math.cos(ph), centre[1] + r * math.cos(th),
                        centre[2] + r * math.sin(th) * math.sin(ph)))
    for i in range(rings):
        for j in range(segs):
            a, b = i * (segs + 1) + j, (i + 1) * (segs + 1) + j
            idx += [a, a + 1, b, a + 1, b + 1, b]
    return pos, idx


def box(lo, hi, n):
    """Closed box, each face n x n quads, counter-clockwise seen from outside."""
    pos, idx = [], []
    for axis in range(3):
        for side in (0, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos)
            for i in range(n + 1):
                for j in range(n + 1):
                    p = [0.0, 0.0, 0.0]
                    p[axis] = hi[axis] if side else lo[axis]
                    p[u] = lo[u] + (hi[u] - lo[u]) * i / n
                    p[v] = lo[v] + (hi[v] - lo[v]) * j / n
                    pos.append(tuple(p))
            for i in range(n):
                for j in range(n):
                    a, b, c, d = base + i * (n + 1) + j, base + (i + 1) * (n + 1) + j, base + (i + 1) * (n + 1) + j + 1, base + i * (n + 1) + j + 1
                    idx += [a, b, c, a, c, d] if side else [a, c, b, a, d, c]
    return pos, idx


def main():
    objects = [
        ("floor", box((-0.2, -0.01, -0.2), (0.2, 0.0, 0.2), 4), 0),
        ("grey_sphere", sphere(0.05, 16, 24, (-0.11, 0.05, 0.0)), 1),
        ("red_sphere", sphere(0.05, 16, 24, (0.0, 0.05, 0.0)), 2),
        ("bending_bar", box((0.09, 0.0, -0.015), (0.12, 0.12, 0.015), 6), 3),
    ]
    buf = bytearray()
    doc = {"asset": {"version": "2.0", "generator": "jade tests/data/make_scene_data.py"},
           "extensionsUsed": ["KHR_materials_volume", "KHR_materials_diffuse_transmission"],
           "bufferViews": [], "accessors": [], "meshes": [], "nodes": [], "scenes": [{"nodes": [0, 1, 2, 3]}], "scene": 0}
    for name, (pos, idx), material in objects:
        view = len(doc["bufferViews"])
        data = b"".join(struct.pack("<3f", *p) for p in pos)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data), "target": 34962})
        buf += data
        lo = [min(p[k] for p in pos) for k in range(3)]
        hi = [max(p[k] for p in pos) for k in range(3)]
        doc["accessors"].append({"bufferView": view, "componentType": FLOAT, "count": len(pos), "type": "VEC3", "min": lo, "max": hi})
        data = struct.pack("<%dI" % len(idx), *idx)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data), "target": 34963})
        buf += data
        doc["accessors"].append({"bufferView": view + 1, "componentType": UINT, "count": len(idx), "type": "SCALAR"})
        doc["meshes"].append({"name": name, "primitives": [{"attributes": {"POSITION": len(doc["accessors"]) - 2},
                                                             "indices": len(doc["accessors"]) - 1, "material": material}]})
        node = {"name": name, "mesh": len(doc["meshes"]) - 1}
        if name == "bending_bar":
            node["extras"] = {"jade": {"deform": "bend", "axis": 1}}
        doc["nodes"].append(node)
    doc["materials"] = [
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1.0], "roughnessFactor": 0.8}},
        {"name": "grey_wax", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "roughnessFactor": 0.4},
         "extensions": {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 1.0},
                        "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationDistance": 0.01}}},
        {"name": "red_jelly", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.5, 0.4, 1.0], "roughnessFactor": 0.3},
         "extensions": {"KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.8,
                                                               "diffuseTransmissionColorFactor": [1.0, 0.6, 0.5]},
                        "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationDistance": 0.02,
                                                 "attenuationColor": [0.9, 0.5, 0.3]}}},
        {"name": "marble_bar", "pbrMetallicRoughness": {"baseColorFactor": [0.85, 0.85, 0.8, 1.0]},
         "extras": {"jade": {"preset": "marble", "mm_per_unit": 1000, "strength": 1.2}}},
    ]
    doc["buffers"] = [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}]
    with open(os.path.join(HERE, "scene_mixed.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
