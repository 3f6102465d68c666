#!/usr/bin/env python3
"""Generates the binary and base64-carrying test files in tests/data (glTF, GLB, PLY) and the
malformed variants in tests/data/bad and tests/data/bad_animation. Deterministic; rerun after
editing, then commit the output:

    python3 tests/data/make_test_data.py

The hand-written text files (cube.obj, cube_colors.off, tetra_normals.off, bad/*.off|ply|obj) and
the files copied from assimp-testmodels (see third_party/ASSETS.md) are not produced here.
"""
import base64
import copy
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
BAD = os.path.join(HERE, "bad")
BAD_ANIMATION = os.path.join(HERE, "bad_animation")

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


def write(path, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(path, mode) as f:
        f.write(data)


class Gltf:
    """A glTF document with a single buffer, built accessor by accessor."""

    def __init__(self):
        self.buffer = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "jade tests/data/make_test_data.py"},
                    "bufferViews": [], "accessors": [], "meshes": [], "nodes": [], "scenes": [], "scene": 0}

    def accessor(self, fmt, values, component, type_, count, target, minmax=False):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        raw = struct.pack("<" + fmt * len(values), *values)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(raw),
                                        "target": target})
        self.buffer += raw
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component, "count": count,
               "type": type_}
        if minmax:
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def vec3(self, points, minmax=False):
        flat = [c for p in points for c in p]
        return self.accessor("f", flat, FLOAT, "VEC3", len(points), ARRAY_BUFFER, minmax)

    def indices(self, values, component):
        fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[component]
        return self.accessor(fmt, values, component, "SCALAR", len(values), ELEMENT_ARRAY_BUFFER)

    def finish(self):
        doc = copy.deepcopy(self.doc)
        doc["buffers"] = [{"byteLength": len(self.buffer),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.buffer)).decode()}]
        return doc

    def glb(self):
        doc = copy.deepcopy(self.doc)
        doc["buffers"] = [{"byteLength": len(self.buffer)}]
        text = json.dumps(doc, separators=(",", ":")).encode()
        text += b" " * (-len(text) % 4)
        binary = bytes(self.buffer) + b"\0" * (-len(self.buffer) % 4)
        total = 12 + 8 + len(text) + 8 + len(binary)
        return (b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(text)) + b"JSON" + text +
                struct.pack("<I", len(binary)) + b"BIN\0" + binary)


def dump(doc):
    return json.dumps(doc, indent=1) + "\n"


# ------------------------------------------------------------------------------ cube_seams --

def cube_faces(lo=-1.0, hi=1.0):
    """Six faces of 4 corners each (counter-clockwise from outside) with the face normal."""
    faces = []
    for a in range(3):
        for side in (0, 1):
            u, v = (a + 1) % 3, (a + 2) % 3
            if side == 0:
                u, v = v, u
            n = [0.0, 0.0, 0.0]
            n[a] = 1.0 if side else -1.0
            corners = []
            for cu, cv in ((lo, lo), (hi, lo), (hi, hi), (lo, hi)):
                p = [0.0, 0.0, 0.0]
                p[a] = hi if side else lo
                p[u], p[v] = cu, cv
                corners.append(p)
            faces.append((corners, n))
    return faces


def cube_seams():
    """A 2x2x2 cube split at every edge like an exporter writes it: 24 vertices, uint16 indices."""
    g = Gltf()
    positions, normals, indices = [], [], []
    for corners, n in cube_faces():
        base = len(positions)
        positions += corners
        normals += [n] * 4
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    pos = g.vec3(positions, minmax=True)
    nrm = g.vec3(normals)
    idx = g.indices(indices, USHORT)
    g.doc["meshes"] = [{"name": "cube", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm},
                                                        "indices": idx, "mode": 4}]}]
    g.doc["nodes"] = [{"mesh": 0, "name": "cube"}]
    g.doc["scenes"] = [{"nodes": [0]}]
    return g


def uv_slab():
    """A slab (0.1 x 0.1 x 0.02, shown at scale 2) with a UV atlas: each face is a 6x6 grid of
    quads in its own tile of a 3x2 layout, with margins between the tiles (seams), and a material
    that Jade maps translucent (extras.jade.preset): what a thickness map is baked for
    (tests/test_baked_asset.cpp)."""
    g = Gltf()
    positions, normals, uvs, indices = [], [], [], []
    size, n, margin = (0.05, 0.05, 0.01), 6, 0.15
    for f, (corners, normal) in enumerate(cube_faces()):
        c0, c1, c3 = corners[0], corners[1], corners[3]
        tile_u, tile_v = (f % 3) / 3.0, (f // 3) / 2.0
        base = len(positions)
        for j in range(n + 1):
            for i in range(n + 1):
                s, t = i / n, j / n
                p = [c0[k] + s * (c1[k] - c0[k]) + t * (c3[k] - c0[k]) for k in range(3)]
                positions.append([p[k] * size[k] for k in range(3)])
                normals.append(normal)
                uvs.append([tile_u + (margin + s * (1 - 2 * margin)) / 3.0,
                            tile_v + (margin + t * (1 - 2 * margin)) / 2.0])
        for j in range(n):
            for i in range(n):
                a = base + j * (n + 1) + i
                indices += [a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]
    pos = g.vec3(positions, minmax=True)
    nrm = g.vec3(normals)
    uv = g.accessor("f", [c for q in uvs for c in q], FLOAT, "VEC2", len(uvs), ARRAY_BUFFER)
    idx = g.indices(indices, USHORT)
    g.doc["materials"] = [{"name": "jade slab", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.8, 0.6, 1.0]},
                           "extras": {"jade": {"preset": "jade"}}}]
    g.doc["meshes"] = [{"name": "slab", "primitives": [{"attributes": {"POSITION": pos, "NORMAL": nrm,
                                                                       "TEXCOORD_0": uv},
                                                        "indices": idx, "material": 0, "mode": 4}]}]
    g.doc["nodes"] = [{"mesh": 0, "name": "slab", "scale": [2.0, 2.0, 2.0]}]
    g.doc["scenes"] = [{"nodes": [0]}]
    return g


def sparse_cube():
    """cube_seams with sparse accessors: POSITION moves vertices 3 and 7 to (0, 0, 5) and
    (0, 0, -5); _AO has no bufferView (zeros) and sparse values 0.25 on vertices 0..3."""
    g = cube_seams()
    doc = g.doc

    def view(fmt, values):
        while len(g.buffer) % 4:
            g.buffer.append(0)
        raw = struct.pack("<" + fmt * len(values), *values)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(g.buffer), "byteLength": len(raw)})
        g.buffer += raw
        return len(doc["bufferViews"]) - 1

    positions = doc["accessors"][0]
    positions["sparse"] = {"count": 2, "indices": {"bufferView": view("H", [3, 7]), "componentType": USHORT},
                           "values": {"bufferView": view("f", [0, 0, 5, 0, 0, -5])}}
    positions["min"][2], positions["max"][2] = -5.0, 5.0
    doc["accessors"].append({"componentType": FLOAT, "count": 24, "type": "SCALAR",
                             "sparse": {"count": 4, "indices": {"bufferView": view("B", [0, 1, 2, 3]), "componentType": UBYTE},
                                        "values": {"bufferView": view("f", [0.25] * 4)}}})
    doc["meshes"][0]["primitives"][0]["attributes"]["_AO"] = len(doc["accessors"]) - 1
    doc["meshes"][0]["name"] = "sparse_cube"
    return g


def asset_features():
    """What the round trip of jade bake must keep (tests/test_gltf_roundtrip.cpp): cube_seams'
    mesh with TEXCOORD_0 and COLOR_0 interleaved in one bufferView (byteStride 12, normalized
    UNSIGNED_BYTE colours), a custom _CUSTOM attribute and a second LINES primitive sharing its
    POSITION accessor; two instances (scale 2, and mirrored), a camera node, and extras and an
    unknown extension on a node, the asset and the document."""
    g = cube_seams()
    doc = g.doc
    while len(g.buffer) % 4:
        g.buffer.append(0)
    offset = len(g.buffer)
    for v in range(24):
        g.buffer += struct.pack("<ff", (v % 4) / 3.0, (v // 4) / 5.0) + struct.pack("<4B", 10 * v, 255 - 10 * v, 128, 255)
    doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": 24 * 12, "byteStride": 12,
                               "target": ARRAY_BUFFER})
    view = len(doc["bufferViews"]) - 1
    doc["accessors"].append({"bufferView": view, "componentType": FLOAT, "count": 24, "type": "VEC2"})
    uv = len(doc["accessors"]) - 1
    doc["accessors"].append({"bufferView": view, "byteOffset": 8, "componentType": UBYTE, "normalized": True,
                             "count": 24, "type": "VEC4"})
    color = len(doc["accessors"]) - 1
    custom = g.accessor("f", [0.5 * v for v in range(24)], FLOAT, "SCALAR", 24, ARRAY_BUFFER)
    lines = g.indices([0, 1, 1, 2, 2, 3, 3, 0], UBYTE)
    prim = doc["meshes"][0]["primitives"][0]
    prim["attributes"].update(TEXCOORD_0=uv, COLOR_0=color, _CUSTOM=custom)
    doc["meshes"][0]["primitives"].append({"attributes": {"POSITION": prim["attributes"]["POSITION"]}, "indices": lines,
                                           "mode": 1})
    doc["nodes"] = [{"mesh": 0, "name": "big", "scale": [2.0, 2.0, 2.0]},
                    {"mesh": 0, "name": "mirrored", "scale": [-1.0, 1.0, 1.0], "translation": [5.0, 0.0, 0.0],
                     "extras": {"note": "kept"}, "extensions": {"EXT_jade_test_unknown": {"level": 3}}},
                    {"name": "eye", "camera": 0, "translation": [0.0, 0.0, 10.0]}]
    doc["scenes"] = [{"nodes": [0, 1, 2], "name": "all"}]
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1, "zfar": 100.0}}]
    doc["extensionsUsed"] = ["EXT_jade_test_unknown"]
    doc["extensions"] = {"EXT_jade_test_unknown": {"document": True}}
    doc["extras"] = {"pipeline": {"stage": 2, "tags": ["a", None, 12345678901234]}}
    doc["asset"]["extras"] = {"author": "make_test_data.py"}
    return g


# ------------------------------------------------------------------------- nodes_transforms --

def nodes_transforms():
    g = Gltf()
    tri = g.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)], minmax=True)
    tri_n = g.vec3([(0, 0, 1)] * 3)
    s = math.sqrt(0.5)
    slope = g.vec3([(1, 0, 0), (0, 1, 0), (1, 0, 1)], minmax=True)
    slope_n = g.vec3([(s, s, 0)] * 3)
    slope_i = g.indices([0, 1, 2], UINT)
    g.doc["meshes"] = [
        {"name": "triangle", "primitives": [{"attributes": {"POSITION": tri, "NORMAL": tri_n}}]},
        {"name": "slope", "primitives": [{"attributes": {"POSITION": slope, "NORMAL": slope_n}, "indices": slope_i}]},
    ]
    g.doc["nodes"] = [
        {"name": "translated", "mesh": 0, "translation": [10, 0, 0]},
        {"name": "trs parent", "translation": [0, 5, 0], "rotation": [0, 0, s, s], "scale": [2, 2, 2], "children": [2]},
        {"name": "matrix child", "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1]},
        {"name": "not in the default scene", "mesh": 0, "translation": [100, 100, 100]},
        {"name": "mirrored", "mesh": 0, "scale": [-1, 1, 1]},
        {"name": "stretched", "mesh": 1, "scale": [2, 1, 1]},
    ]
    g.doc["scenes"] = [{"nodes": [3]}, {"nodes": [0, 1, 4, 5]}]
    g.doc["scene"] = 1
    return g


# ------------------------------------------------------------------------------ strip_fan --

def strip_fan():
    g = Gltf()
    strip = g.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 2, 0), (1, 2, 0)])
    ring = [(5, 0, 0)] + [(5 + math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0) for k in range(6)]
    fan = g.vec3(ring)
    fan_i = g.indices([0, 1, 2, 3, 4, 5, 6, 1], UBYTE)
    g.doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": strip}, "mode": 5},
                                       {"attributes": {"POSITION": fan}, "indices": fan_i, "mode": 6}]}]
    g.doc["nodes"] = [{"mesh": 0}]
    g.doc["scenes"] = [{"nodes": [0]}]
    return g


# ------------------------------------------------------------------------------------ PLY --

def unit_cube():
    positions = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    index = {p: i for i, p in enumerate(positions)}
    quads = []
    for corners, _ in cube_faces(0.0, 1.0):
        quads.append([index[tuple(int(c) for c in p)] for p in corners])
    normals = [tuple((2 * c - 1) / math.sqrt(3) for c in p) for p in positions]
    return positions, normals, quads


PLY_TYPES = {"uchar": "B", "char": "b", "ushort": "H", "short": "h", "int": "i", "uint": "I", "float": "f",
             "double": "d"}


def ply_cube(fmt, count_type, index_type, index_name, faces_first):
    """The unit cube with quads, per-vertex normals, and properties and elements to skip."""
    positions, normals, quads = unit_cube()
    vertex_props = [("float", "x"), ("uchar", "red"), ("double", "y"), ("float", "nx"), ("float", "ny"),
                    ("float", "nz"), ("float", "z"), ("uchar", "green")]
    vertex_header = "element vertex 8\n" + "".join(f"property {t} {n}\n" for t, n in vertex_props)
    vertex_header += "property list uchar short tags\n"
    face_header = (f"element face 6\nproperty uchar intensity\nproperty list {count_type} {index_type} {index_name}\n"
                   "property float quality\n")
    edge_header = "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty list uchar float weights\n"
    body_order = ["face", "vertex", "edge"] if faces_first else ["vertex", "edge", "face"]
    headers = {"vertex": vertex_header, "face": face_header, "edge": edge_header}
    header = f"ply\nformat {fmt} 1.0\ncomment unit cube for jade tests\nobj_info generated\n"
    header += "".join(headers[e] for e in body_order) + "end_header\n"

    def vertex_values(i):
        p, n = positions[i], normals[i]
        return [("f", p[0]), ("B", 10 * i), ("d", p[1]), ("f", n[0]), ("f", n[1]), ("f", n[2]), ("f", p[2]),
                ("B", 255 - i)], [("h", -i), ("h", i)]

    records = {"vertex": [], "face": [], "edge": []}
    for i in range(8):
        scalars, tags = vertex_values(i)
        records["vertex"].append(scalars + [("B", len(tags))] + tags)
    for f, q in enumerate(quads):
        records["face"].append([("B", 100 + f), (PLY_TYPES[count_type], len(q))] + [(PLY_TYPES[index_type], v) for v in q]
                               + [("f", 0.5 * f)])
    records["edge"] = [[("i", 0), ("i", 1), ("B", 2), ("f", 0.25), ("f", 0.75)], [("i", 2), ("i", 3), ("B", 0)]]

    if fmt == "ascii":
        lines = []
        for e in body_order:
            for r in records[e]:
                lines.append(" ".join(repr(float(v)) if c in "fd" else str(v) for c, v in r))
        return (header + "\n".join(lines) + "\n").encode()
    endian = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(endian + c, v) for e in body_order for r in records[e] for c, v in r)
    return header.encode() + body


# ----------------------------------------------------------------------------- bad files --

def bad_gltf_files():
    """Malformed variants of cube_seams.gltf: name -> document (or raw text)."""
    base = cube_seams()
    doc = base.finish()
    out = {}

    def variant(name, edit):
        d = copy.deepcopy(doc)
        edit(d)
        out[name] = d

    prim = lambda d: d["meshes"][0]["primitives"][0]
    variant("gltf_points.gltf", lambda d: prim(d).update(mode=0))
    variant("gltf_lines.gltf", lambda d: prim(d).update(mode=1))
    variant("gltf_draco_required.gltf", lambda d: d.update(extensionsUsed=["KHR_draco_mesh_compression"],
                                                           extensionsRequired=["KHR_draco_mesh_compression"]))
    variant("gltf_meshopt_required.gltf", lambda d: d.update(extensionsUsed=["EXT_meshopt_compression"],
                                                             extensionsRequired=["EXT_meshopt_compression"]))
    variant("gltf_sparse_count.gltf", lambda d: d["accessors"][0].update(
        sparse={"count": 100, "indices": {"bufferView": 2, "componentType": USHORT},
                "values": {"bufferView": 0}}))
    # Entries 0 and 1 of the index buffer (0, 1, 2, 0, ...) as sparse indices, then 2 and 0.
    variant("gltf_sparse_unordered.gltf", lambda d: d["accessors"][0].update(
        sparse={"count": 4, "indices": {"bufferView": 2, "componentType": USHORT},
                "values": {"bufferView": 0}}))
    variant("gltf_view_past_buffer.gltf", lambda d: d["bufferViews"][1].update(byteLength=4000))
    variant("gltf_accessor_past_view.gltf", lambda d: d["accessors"][0].update(count=25))
    variant("gltf_int_positions.gltf", lambda d: d["accessors"][0].update(componentType=UINT))
    variant("gltf_vec2_positions.gltf", lambda d: d["accessors"][0].update(type="VEC2"))
    variant("gltf_stride_too_small.gltf", lambda d: d["bufferViews"][0].update(byteStride=8))
    variant("gltf_normal_count_mismatch.gltf", lambda d: d["accessors"][1].update(count=3))
    variant("gltf_indices_not_multiple_of_3.gltf", lambda d: d["accessors"][2].update(count=35))
    variant("gltf_missing_node.gltf", lambda d: d["scenes"][0].update(nodes=[0, 5]))
    variant("gltf_missing_mesh.gltf", lambda d: d["nodes"][0].update(mesh=3))
    variant("gltf_missing_accessor.gltf", lambda d: prim(d)["attributes"].update(POSITION=9))
    variant("gltf_no_position.gltf", lambda d: prim(d)["attributes"].pop("POSITION"))
    variant("gltf_missing_scene.gltf", lambda d: d.update(scene=2))
    variant("gltf_short_data_uri.gltf", lambda d: d["buffers"][0].update(byteLength=d["buffers"][0]["byteLength"] + 64))

    def two_parents(d):
        d["nodes"] = [{"children": [2]}, {"children": [2]}, {"mesh": 0}]
        d["scenes"][0]["nodes"] = [0, 1]
    variant("gltf_two_parents.gltf", two_parents)

    # Index 24 in a 24-vertex primitive: the last index of the last triangle.
    raw = bytearray(base.buffer)
    offset = doc["bufferViews"][2]["byteOffset"] + 35 * 2
    raw[offset:offset + 2] = struct.pack("<H", 24)
    d = copy.deepcopy(doc)
    d["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(raw)).decode()
    out["gltf_index_out_of_range.gltf"] = d

    # External files that are not the glTF's own folder or below it: a relative path climbing out
    # of the folder to a file that exists and would load (tests/data/cube_external.bin), the same
    # percent-encoded, an absolute path, a file: URL, and an image (read but never decoded).
    def external(uri):
        return lambda d: d["buffers"][0].update(uri=uri)
    variant("gltf_uri_parent.gltf", external("../cube_external.bin"))
    variant("gltf_uri_percent_parent.gltf", external("%2E%2E/cube_external.bin"))
    variant("gltf_uri_absolute.gltf", external("/etc/passwd"))
    variant("gltf_uri_file_scheme.gltf", external("file:///etc/passwd"))
    variant("gltf_image_uri_parent.gltf", lambda d: d.update(images=[{"uri": "../cube_external.bin"}]))

    texts = {name: dump(d) for name, d in out.items()}
    texts["gltf_truncated_json.gltf"] = dump(doc)[:300]
    return texts


def bad_glb_files():
    glb = cube_seams().glb()
    out = {
        "glb_truncated.glb": glb[: len(glb) // 2],
        "glb_bad_magic.glb": b"glTX" + glb[4:],
        "glb_version1.glb": glb[:4] + struct.pack("<I", 1) + glb[8:],
    }
    # BIN chunk length 64 bytes more than the file holds.
    json_len = struct.unpack_from("<I", glb, 12)[0]
    bin_at = 20 + json_len
    bin_len = struct.unpack_from("<I", glb, bin_at)[0]
    out["glb_bin_chunk_too_long.glb"] = glb[:bin_at] + struct.pack("<I", bin_len + 64) + glb[bin_at + 4:]
    return out


def bad_ply_files():
    cube = ply_cube("binary_little_endian", "uchar", "int", "vertex_indices", False)
    header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
              b"property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")
    return {
        "ply_absurd_count.ply": header + struct.pack("<3f", 0, 0, 0),
        "ply_truncated.ply": cube[: len(cube) - 40],
    }


def skinned_morph_anim():
    """A closed square column (0.5 x 2 x 0.5, rings at y = 0, 0.5, ..., 2) skinned to two joints,
    with one morph target and an animation whose three channels use the three sampler types.
    tests/test_deform.cpp hand-computes the expected pose from the numbers written here:
      node 0  the mesh, skin 0 (tests/test_deform.cpp gives it a translation in memory, which a
              skinned mesh ignores: glTF validators warn about one in a file)
      node 1  joint "root" at the origin; node 2 joint "upper", child of 1, translation (0, 1, 0)
      weights: rings y <= 0.5 -> root, y = 1 -> 0.5 / 0.5, y >= 1.5 -> upper
      morph target 0: the top ring (y = 2) moves by (+0.1 x, 0, +0.1 z) (it widens by 20 %)
      animation 0: node 2 rotation LINEAR keys 0, 1 s: identity -> 90 deg about z
                   node 1 translation STEP keys 0, 0.5, 1 s: (0,0,0), (1,0,0), (2,0,0)
                   node 0 weights CUBICSPLINE keys 0, 1 s: [in 0, value 0, out 2], [in 0, value 1, out 0]
    """
    g = Gltf()
    h = 0.25
    square = [(-h, -h), (h, -h), (h, h), (-h, h)]
    rings = [0.0, 0.5, 1.0, 1.5, 2.0]
    pos = [(x, y, z) for y in rings for (x, z) in square]
    idx = []
    for r in range(len(rings) - 1):
        for k in range(4):
            a, b = 4 * r + k, 4 * r + (k + 1) % 4
            c, d = a + 4, b + 4
            idx += [a, c, b, b, c, d]  # counter-clockwise seen from outside
    top = 4 * (len(rings) - 1)
    idx += [0, 1, 2, 0, 2, 3]                      # bottom, facing -y
    idx += [top, top + 2, top + 1, top, top + 3, top + 2]  # top, facing +y
    joints, weights = [], []
    for (x, y, z) in pos:
        w1 = 0.0 if y <= 0.5 else (0.5 if y == 1.0 else 1.0)
        joints += [0, 1 if w1 > 0.0 else 0, 0, 0]  # unused slots hold joint 0, as glTF asks
        weights += [1.0 - w1, w1, 0.0, 0.0]
    delta = [(0.1 * x, 0.0, 0.1 * z) if y == 2.0 else (0.0, 0.0, 0.0) for (x, y, z) in pos]
    p_acc = g.vec3(pos, minmax=True)
    i_acc = g.indices(idx, USHORT)
    j_acc = g.accessor("B", joints, UBYTE, "VEC4", len(pos), ARRAY_BUFFER)
    w_acc = g.accessor("f", weights, FLOAT, "VEC4", len(pos), ARRAY_BUFFER)
    d_acc = g.vec3(delta, minmax=True)
    ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]  # column-major: identity, translate(0,-1,0)
    ibm_acc = g.accessor("f", ibm, FLOAT, "MAT4", 2, None)
    del g.doc["bufferViews"][-1]["target"]
    s = math.sin(math.pi / 4)
    t_rot = g.accessor("f", [0.0, 1.0], FLOAT, "SCALAR", 2, None)
    g.doc["accessors"][-1].update(min=[0.0], max=[1.0])  # glTF requires bounds on key times
    del g.doc["bufferViews"][-1]["target"]
    v_rot = g.accessor("f", [0, 0, 0, 1, 0, 0, s, s], FLOAT, "VEC4", 2, None)
    del g.doc["bufferViews"][-1]["target"]
    t_step = g.accessor("f", [0.0, 0.5, 1.0], FLOAT, "SCALAR", 3, None)
    g.doc["accessors"][-1].update(min=[0.0], max=[1.0])
    del g.doc["bufferViews"][-1]["target"]
    v_step = g.accessor("f", [0, 0, 0, 1, 0, 0, 2, 0, 0], FLOAT, "VEC3", 3, None)
    del g.doc["bufferViews"][-1]["target"]
    v_cubic = g.accessor("f", [0.0, 0.0, 2.0, 0.0, 1.0, 0.0], FLOAT, "SCALAR", 6, None)
    del g.doc["bufferViews"][-1]["target"]
    g.doc["meshes"].append({"primitives": [{"attributes": {"POSITION": p_acc, "JOINTS_0": j_acc, "WEIGHTS_0": w_acc},
                                            "indices": i_acc, "targets": [{"POSITION": d_acc}]}],
                            "weights": [0.0]})
    g.doc["nodes"] = [{"name": "column", "mesh": 0, "skin": 0},
                      {"name": "root", "children": [2]},
                      {"name": "upper", "translation": [0.0, 1.0, 0.0]}]
    g.doc["skins"] = [{"joints": [1, 2], "inverseBindMatrices": ibm_acc, "skeleton": 1}]
    g.doc["scenes"] = [{"nodes": [0, 1]}]
    g.doc["animations"] = [{"name": "bend_slide_bulge",
                            "samplers": [{"input": t_rot, "output": v_rot, "interpolation": "LINEAR"},
                                         {"input": t_step, "output": v_step, "interpolation": "STEP"},
                                         {"input": t_rot, "output": v_cubic, "interpolation": "CUBICSPLINE"}],
                            "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}},
                                         {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                                         {"sampler": 2, "target": {"node": 0, "path": "weights"}}]}]
    return g

def bad_animation_files():
    """Malformed variants of skinned_morph_anim.gltf for load_animated_gltf (tests/test_deform.cpp),
    in tests/data/bad_animation."""
    good = skinned_morph_anim().finish()

    def variant(edit):
        d = copy.deepcopy(good)
        edit(d)
        return dump(d)

    def set_(path, value):
        def edit(d):
            node = d
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = value
        return edit

    return {
        "anim_bad_interpolation.gltf": variant(set_(["animations", 0, "samplers", 1, "interpolation"], "SMOOTH")),
        "anim_bad_joint.gltf": variant(set_(["skins", 0, "joints"], [1, 7])),
        "anim_cycle.gltf": variant(set_(["nodes", 2, "children"], [1])),
        "anim_bad_target.gltf": variant(set_(["animations", 0, "channels", 0, "target", "node"], 9)),
        # sampler 1 (STEP, 3 translation keys) given the 2-key time accessor of sampler 0
        "anim_output_count.gltf": variant(set_(["animations", 0, "samplers", 1, "input"], 6)),
    }


def main():
    os.makedirs(BAD, exist_ok=True)
    write(os.path.join(HERE, "cube_seams.gltf"), dump(cube_seams().finish()))
    write(os.path.join(HERE, "cube_seams.glb"), cube_seams().glb())
    external = cube_seams()
    doc = external.finish()
    doc["buffers"][0]["uri"] = "cube_external.bin"
    write(os.path.join(HERE, "cube_external.gltf"), dump(doc))
    write(os.path.join(HERE, "cube_external.bin"), bytes(external.buffer))
    write(os.path.join(HERE, "nodes_transforms.gltf"), dump(nodes_transforms().finish()))
    write(os.path.join(HERE, "strip_fan.gltf"), dump(strip_fan().finish()))
    write(os.path.join(HERE, "sparse_cube.gltf"), dump(sparse_cube().finish()))
    write(os.path.join(HERE, "uv_slab.gltf"), dump(uv_slab().finish()))
    write(os.path.join(HERE, "asset_features.gltf"), dump(asset_features().finish()))
    write(os.path.join(HERE, "skinned_morph_anim.gltf"), dump(skinned_morph_anim().finish()))
    # Not in bad/: those must all fail load_mesh, which ignores animations.
    os.makedirs(BAD_ANIMATION, exist_ok=True)
    for name, data in bad_animation_files().items():
        write(os.path.join(BAD_ANIMATION, name), data)
    write(os.path.join(HERE, "cube_ascii.ply"), ply_cube("ascii", "uchar", "int", "vertex_indices", False))
    write(os.path.join(HERE, "cube_binary_le.ply"), ply_cube("binary_little_endian", "int", "uint", "vertex_index", False))
    write(os.path.join(HERE, "cube_binary_be.ply"), ply_cube("binary_big_endian", "uint", "int", "vertex_indices", True))
    for name, data in {**bad_gltf_files(), **bad_glb_files(), **bad_ply_files()}.items():
        write(os.path.join(BAD, name), data)


if __name__ == "__main__":
    main()
