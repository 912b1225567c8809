#!/usr/bin/env python3
"""Writes the loader corpus of crates/core/tests/corpus.rs: spec-valid edge cases and broken
glTF, GLB and OBJ files, each named for what it holds. Run from this folder; needs Pillow only
for the WebP texture (pip install pillow). The files are committed: CI does not run this.
"""
import base64
import io
import json
import math
import struct

from PIL import Image


def strip(n, y=0.0):
    """n triangles as a strip of unit quads along x (n even): positions, indices."""
    pos, idx = [], []
    for q in range(n // 2):
        x = float(q)
        base = len(pos)
        pos += [(x, y, 0.0), (x + 1, y, 0.0), (x + 1, y, 1.0), (x, y, 1.0)]
        idx += [base, base + 2, base + 1, base, base + 3, base + 2]
    return pos, idx


class Gltf:
    """A one-mesh glTF document with one binary buffer, built accessor by accessor."""

    def __init__(self):
        self.bin = bytearray()
        self.doc = {
            "asset": {"version": "2.0"},
            "scenes": [{"nodes": [0]}],
            "scene": 0,
            "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {}}]}],
            "buffers": [],
            "bufferViews": [],
            "accessors": [],
        }

    def prim(self):
        return self.doc["meshes"][0]["primitives"][0]

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, fmt, component, kind, values, normalized=False, view=True, **extra):
        acc = {"componentType": component, "type": kind, "count": len(values)}
        if view:
            flat = [c for v in values for c in (v if isinstance(v, tuple) else (v,))]
            acc["bufferView"] = self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat))
        if normalized:
            acc["normalized"] = True
        if kind == "VEC3" and component == 5126 and view:
            acc["min"] = [min(v[i] for v in values) for i in range(3)]
            acc["max"] = [max(v[i] for v in values) for i in range(3)]
        acc.update(extra)
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def positions(self, pos):
        self.prim()["attributes"]["POSITION"] = self.accessor("f", 5126, "VEC3", pos)

    def indices(self, idx):
        self.prim()["indices"] = self.accessor("I", 5125, "SCALAR", idx)

    def finish(self):
        self.doc["buffers"] = [{"byteLength": len(self.bin)}]
        return self

    def gltf(self, name):
        self.finish()
        self.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + \
            base64.b64encode(bytes(self.bin)).decode()
        with open(name, "w") as f:
            json.dump(self.doc, f, indent=1)

    def glb(self, name, trailing=b""):
        self.finish()
        js = json.dumps(self.doc).encode()
        js += b" " * (-len(js) % 4)
        binary = bytes(self.bin) + b"\0" * (-len(self.bin) % 4)
        body = struct.pack("<I4s", len(js), b"JSON") + js + \
            struct.pack("<I4s", len(binary), b"BIN\0") + binary
        with open(name, "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(body) + len(trailing)) + body + trailing)


def plain(n=2):
    g = Gltf()
    pos, idx = strip(n)
    g.positions(pos)
    g.indices(idx)
    return g


def textured(texture):
    """A quad with TEXCOORD_0 and a material whose base colour uses `texture`."""
    g = plain()
    g.prim()["attributes"]["TEXCOORD_0"] = g.accessor(
        "f", 5126, "VEC2", [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    g.prim()["material"] = 0
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    g.doc["textures"] = [texture]
    return g


def image_bytes(fmt):
    buf = io.BytesIO()
    Image.new("RGB", (2, 2), (255, 0, 0)).save(buf, fmt, **({"lossless": True} if fmt == "WEBP" else {}))
    return buf.getvalue()


# --- spec-valid files the gltf crate's strict validation refused ---

# TEXCOORD_0 accessor without a buffer view: zeros.
g = plain()
g.prim()["attributes"]["TEXCOORD_0"] = g.accessor("f", 5126, "VEC2", [(0, 0)] * 4, view=False)
g.gltf("valid-accessor-without-buffer-view.gltf")

# Sparse POSITION without a buffer view: zeros with four vertices replaced (one quad).
g = Gltf()
pos, idx = strip(2)
zeros = [(0.0, 0.0, 0.0)] * 8
acc = g.accessor("f", 5126, "VEC3", zeros, view=False, min=[0, 0, 0], max=[1, 0, 1])
g.doc["accessors"][acc]["sparse"] = {
    "count": 4,
    "indices": {"bufferView": g.view(struct.pack("<4B", 4, 5, 6, 7)), "componentType": 5121},
    "values": {"bufferView": g.view(struct.pack("<12f", *[c for p in pos for c in p]))},
}
g.prim()["attributes"]["POSITION"] = acc
g.indices([i + 4 for i in idx])
g.gltf("valid-sparse-positions.gltf")

# A texture whose image comes only through EXT_texture_webp (decoded).
g = textured({"extensions": {"EXT_texture_webp": {"source": 0}}})
g.doc["images"] = [{"bufferView": g.view(image_bytes("WEBP")), "mimeType": "image/webp"}]
g.doc["extensionsUsed"] = ["EXT_texture_webp"]
g.glb("valid-webp-only-texture.glb")

# A texture whose image comes only through KHR_texture_basisu (optional: not decodable).
g = textured({"extensions": {"KHR_texture_basisu": {"source": 0}}})
g.doc["images"] = [{"uri": "missing.ktx2", "mimeType": "image/ktx2"}]
g.doc["extensionsUsed"] = ["KHR_texture_basisu"]
g.gltf("valid-ktx2-only-texture-optional.gltf")

# A texture without any image at all.
g = textured({"sampler": 0})
g.doc["samplers"] = [{}]
g.gltf("valid-texture-without-image.gltf")

# An animation channel without a target node (the channel is to be ignored).
g = plain()
t = g.accessor("f", 5126, "SCALAR", [0.0, 1.0], min=[0.0], max=[1.0])
v = g.accessor("f", 5126, "VEC3", [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)])
g.doc["animations"] = [{
    "samplers": [{"input": t, "output": v}],
    "channels": [{"sampler": 0, "target": {"path": "translation"}}],
}]
g.gltf("valid-animation-channel-without-node.gltf")

# A GLB with bytes after its last chunk (inside the declared length).
plain().glb("valid-glb-trailing-bytes.glb", trailing=b"\0\0\0\0")

# KHR_mesh_quantization (required): normalized i16 positions, u8 normalized texcoords.
g = Gltf()
g.doc["extensionsUsed"] = ["KHR_mesh_quantization"]
g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
g.prim()["attributes"]["POSITION"] = g.accessor(
    "h", 5122, "VEC3", [(0, 0, 0), (32767, 0, 0), (32767, 0, 32767), (0, 0, 32767), (0, 0, 0)],
    normalized=True, min=[0, 0, 0], max=[32767, 0, 32767])
g.prim()["attributes"]["TEXCOORD_0"] = g.accessor(
    "B", 5121, "VEC2", [(0, 0), (255, 0), (255, 255), (0, 255), (0, 0)], normalized=True)
g.prim()["indices"] = g.accessor("H", 5123, "SCALAR", [0, 2, 1, 0, 3, 2])
g.doc["nodes"][0]["scale"] = [2.0, 2.0, 2.0]
g.gltf("valid-mesh-quantization.gltf")

# An optional extension slc does not model (noted, not refused).
g = plain()
g.doc["extensionsUsed"] = ["KHR_materials_clearcoat"]
g.gltf("valid-optional-unknown-extension.gltf")

# --- required extensions slc cannot read ---
for ext in ["KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_texture_basisu"]:
    g = plain()
    g.doc["extensionsUsed"] = [ext]
    g.doc["extensionsRequired"] = [ext]
    g.gltf("unsupported-required-%s.gltf" % ext)

# --- damaged geometry ---
# 1 of 20 triangles with an index past the vertex count: removed with a warning.
g = Gltf()
pos, idx = strip(20)
idx[-1] = 999
g.positions(pos)
g.indices(idx)
g.gltf("damaged-one-index-past-end.gltf")

# 3 of 20 triangles with non-finite positions: more than 10%, refused.
g = Gltf()
pos, idx = strip(20)
pos[0] = (math.nan, 0.0, 0.0)
pos[5] = (math.inf, 0.0, 0.0)
g.prim()["attributes"]["POSITION"] = g.accessor("f", 5126, "VEC3", pos, min=[0, 0, 0], max=[10, 0, 1])
g.indices(idx)
g.gltf("damaged-non-finite-positions.gltf")

# A GLB whose declared length is beyond the file, and one below its header.
with open("damaged-glb-truncated.glb", "wb") as f:
    f.write(struct.pack("<4sII", b"glTF", 2, 4096) + b"\0" * 20)
with open("damaged-glb-length-below-header.glb", "wb") as f:
    f.write(struct.pack("<4sII", b"glTF", 2, 4))

# OBJ: non-finite and overflowing vertices (2 of 3 triangles), one bad normal index, one bad
# texture-coordinate index.
QUAD = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
with open("damaged-obj-non-finite-vertices.obj", "w") as f:
    f.write(QUAD + "v nan 0 0\nv 0 inf 0\nv 1e39 0 0\nf 1 3 2\nf 1 5 2\nf 6 7 3\n")
with open("damaged-obj-normal-index.obj", "w") as f:
    f.write(QUAD + "vn 0 1 0\nf 1//1 3//1 2//7\n")
with open("damaged-obj-texcoord-index.obj", "w") as f:
    f.write(QUAD + "vt 0 0\nf 1/1 3/1 2/9\n")
with open("valid-obj-one-zero-area-triangle.obj", "w") as f:
    f.write(QUAD + "f 1 3 2\nf 1 4 3\nf 1 2 1\n")

# --- what the specification allows, and what nothing uses (issue 43) ---


def floats_for_integers(value):
    """Every integer of a JSON document written as a float (1 -> 1.0)."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        return float(value)
    if isinstance(value, list):
        return [floats_for_integers(v) for v in value]
    if isinstance(value, dict):
        return {k: floats_for_integers(v) for k, v in value.items()}
    return value


# A second buffer without `uri` in a .gltf: only a GLB's first buffer may lack one, but nothing
# reads this one.
g = plain()
g.finish()
g.doc["buffers"].append({"byteLength": 16})
g.gltf("valid-unused-buffer-without-uri.gltf")

# A GLB without a BIN chunk whose buffer is a data: URI.
g = plain()
g.finish()
g.doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + \
    base64.b64encode(bytes(g.bin)).decode()
js = json.dumps(g.doc).encode()
js += b" " * (-len(js) % 4)
with open("valid-glb-data-uri-buffer.glb", "wb") as f:
    f.write(struct.pack("<4sII", b"glTF", 2, 20 + len(js)) + struct.pack("<I4s", len(js), b"JSON") + js)

# Every integer written as a float (JSON numbers; 1.0 is the integer 1).
g = plain()
g.gltf("valid-integers-written-as-floats.gltf")
with open("valid-integers-written-as-floats.gltf") as f:
    doc = json.load(f)
with open("valid-integers-written-as-floats.gltf", "w") as f:
    json.dump(floats_for_integers(doc), f, indent=1)

# A scene without `nodes` (optional) beside the default scene that has them.
g = plain()
g.doc["scenes"] = [{"name": "empty"}, {"nodes": [0]}]
g.doc["scene"] = 1
g.gltf("valid-scene-without-nodes.gltf")

# A primitive without POSITION (optional: it is not rendered) beside one with it.
g = plain()
g.doc["meshes"][0]["primitives"].append({"attributes": {}})
g.gltf("valid-primitive-without-position.gltf")

# An accessor of a type that is no glTF type, used by nothing.
g = plain()
g.doc["accessors"].append({"componentType": 5126, "type": "MAT5", "count": 1})
g.gltf("valid-unused-accessor-of-unknown-type.gltf")

# A spot light with outerConeAngle 0 (the schema's minimum; but the specification asks
# innerConeAngle < outerConeAngle, and a cone of 0 emits nothing): dropped with a warning.
g = plain()
g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "spot": {"outerConeAngle": 0.0}}]}}
g.doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0]})
g.doc["scenes"][0]["nodes"].append(1)
g.gltf("valid-spot-outer-cone-0.gltf")

# Versions a glTF 2.0 loader does not know.
g = plain()
g.doc["asset"]["version"] = "3.0"
g.gltf("unsupported-asset-version-3.0.gltf")
g = plain()
g.doc["asset"]["minVersion"] = "2.5"
g.gltf("unsupported-min-version-2.5.gltf")

# OBJ: a usemtl name no material library defines.
with open("valid-obj-usemtl-undefined.obj", "w") as f:
    f.write(QUAD + "usemtl light\nf 1 3 2\n")
