#!/usr/bin/env python3
"""Generates the `materials` test scene: a glossy normal-mapped floor and a double-sided,
alpha-masked sheet in a Cornell-like room (see README.md in reference/ for the conventions).

Writes, beside this file (deterministic, byte-identical on every run):
  materials.gltf       glTF 2.0 JSON (7 nodes: 6 meshes, camera; KHR_lights_punctual point light)
  materials.bin        float32 POSITION / NORMAL / TEXCOORD_0, uint32 indices
  ridges_normal.png    64x64 RGB 8-bit tangent-space normal map (glTF convention)
  holes_color.png      64x64 RGBA 8-bit base colour with a strictly binary alpha mask

Pure Python 3 standard library (json, math, struct, zlib).

Conventions: metres, +y up, right-handed; every mesh in world coordinates (mesh nodes have no
transform); each quad has 4 vertices and the triangles (0,1,2), (0,2,3), counter-clockwise seen
from the side its normal points to; no TANGENT attribute anywhere (a renderer must generate
MikkTSpace-equivalent tangents: for the floor T = +x, B = cross(N, T) * w = -z with w = +1,
i.e. B points towards decreasing v = the normal map's +Y = "up" in the image).
"""
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
NAME = "materials"
TEX_N = 64  # both textures are TEX_N x TEX_N

# ----------------------------------------------------------------------------------------------
# PNG writing (8-bit RGB or RGBA, no interlace, filter 0 on every row)
# ----------------------------------------------------------------------------------------------


def png_bytes(width, height, rows, channels):
    """rows: list of `height` lists of width*channels ints in 0..255, row 0 = top of the image."""
    color_type = {3: 2, 4: 6}[channels]

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data
                + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))

    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    ihdr = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr)
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# ----------------------------------------------------------------------------------------------
# ridges_normal.png: h(i, j) = A sin(2 pi (i + 2 (63 - j)) / 32) in texel units (i = column,
# j = row from the top, j_up = 63 - j grows towards the top of the image = the map's +Y).
# Periods: 32 texels along i, 16 along j: both divide 64, so the map tiles seamlessly.
# n = normalize(-dh/di, -dh/dj_up, 1) (analytic). Largest tilt: atan(|grad h|max) = 25 deg.
# The ridges run along a diagonal, so the pattern is not symmetric under y -> -y (a renderer
# with the bitangent's sign flipped sees a different, mirrored, set of highlights).
# ----------------------------------------------------------------------------------------------
RIDGE_PERIOD = 32.0
RIDGE_MAX_TILT_DEG = 25.0
RIDGE_K = 2.0 * math.pi / RIDGE_PERIOD
# |grad h| max = A K sqrt(1^2 + 2^2)
RIDGE_A = math.tan(math.radians(RIDGE_MAX_TILT_DEG)) / (RIDGE_K * math.sqrt(5.0))


def ridge_normal(i, j):
    """Unit tangent-space normal of texel (column i, row j from the top), at the texel centre."""
    j_up = (TEX_N - 1) - j
    c = math.cos(RIDGE_K * (i + 2.0 * j_up))
    dh_di = RIDGE_A * RIDGE_K * c
    dh_dj_up = 2.0 * RIDGE_A * RIDGE_K * c
    n = (-dh_di, -dh_dj_up, 1.0)
    length = math.sqrt(sum(x * x for x in n))
    return tuple(x / length for x in n)


def ridges_rows():
    rows = []
    for j in range(TEX_N):
        row = []
        for i in range(TEX_N):
            n = ridge_normal(i, j)
            row.extend(int(round((x + 1.0) * 0.5 * 255.0)) for x in n)
        rows.append(row)
    return rows


# ----------------------------------------------------------------------------------------------
# holes_color.png: orange (230,130,50) with a blue (40,80,200) stripe on the top 8 rows and a
# dark-red (120,20,20) 8x8 block at the top-left corner (rows 0..7, columns 0..7) so that
# both axes' orientation can be read off a render; alpha 0 inside a 4x4 grid of round holes
# (centres at texel-centre coordinates (8 + 16a, 8 + 16b), radius 5 texels: a texel is a hole if
# its centre (i + 0.5, j + 0.5) lies within 5 of the hole centre), 255 elsewhere.
# ----------------------------------------------------------------------------------------------
ORANGE = (230, 130, 50)
BLUE = (40, 80, 200)
DARK_RED = (120, 20, 20)
HOLE_RADIUS = 5.0


def is_hole(i, j):
    x, y = i + 0.5, j + 0.5
    for a in range(4):
        for b in range(4):
            cx, cy = 8.0 + 16.0 * a, 8.0 + 16.0 * b
            if (x - cx) ** 2 + (y - cy) ** 2 <= HOLE_RADIUS ** 2:
                return True
    return False


def holes_rows():
    rows = []
    for j in range(TEX_N):
        row = []
        for i in range(TEX_N):
            if j < 8 and i < 8:
                rgb = DARK_RED
            elif j < 8:
                rgb = BLUE
            else:
                rgb = ORANGE
            row.extend(rgb)
            row.append(0 if is_hole(i, j) else 255)
        rows.append(row)
    return rows


# ----------------------------------------------------------------------------------------------
# Geometry
# ----------------------------------------------------------------------------------------------


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    length = math.sqrt(sum(x * x for x in a))
    return tuple(x / length for x in a)


def quad(corners, uvs=None):
    """4 corners in counter-clockwise order seen from the normal's side; normal =
    normalize((c1 - c0) x (c2 - c0)), stored per vertex; triangles (0,1,2), (0,2,3)."""
    n = normalize(cross(sub(corners[1], corners[0]), sub(corners[2], corners[0])))
    # the quad must be planar with the same normal for both triangles
    n2 = normalize(cross(sub(corners[2], corners[0]), sub(corners[3], corners[0])))
    assert max(abs(a - b) for a, b in zip(n, n2)) < 1e-12, (n, n2)
    return {"positions": list(corners), "normals": [n] * 4, "uvs": uvs, "indices": [0, 1, 2, 0, 2, 3]}


# Room [-1,1] x [0,2] x [-1,1], open at z = +1; quads p0, p0+eu, p0+eu+ev, p0+ev (as cornell-a).
def wall(p0, eu, ev, uv_of=None):
    c = [p0, tuple(a + b for a, b in zip(p0, eu)),
         tuple(a + b + d for a, b, d in zip(p0, eu, ev)), tuple(a + b for a, b in zip(p0, ev))]
    return quad(c, [uv_of(p) for p in c] if uv_of else None)


def floor_uv(p):
    # u = 2 (x + 1), v = 2 (z + 1): the texture repeats twice along x and z; u grows with +x,
    # v grows with +z (towards the camera).
    return (2.0 * (p[0] + 1.0), 2.0 * (p[2] + 1.0))


# The sheet: corners given bottom-back (y 0.35, z -0.55) to top-front (y 1.15, z -0.15).
SHEET_P0 = (-0.6, 0.35, -0.55)
SHEET_P1 = (0.4, 0.35, -0.55)
SHEET_P2 = (0.4, 1.15, -0.15)
SHEET_P3 = (-0.6, 1.15, -0.15)


def sheet():
    # UV: image top (v = 0, blue stripe) along the top edge (y = 1.15), u = 0 at x = -0.6, so the
    # image reads upright and unmirrored from the camera. The AUTHORED normal must point away
    # from the camera and the light: (p1 - p0) x (p2 - p0) = (0, -0.4, 0.8) points towards the
    # camera (+z), so the corners are listed in the opposite order p0, p3, p2, p1, giving
    # normal (0, 0.4, -0.8) / |.| = (0, 0.447, -0.894) (up and back).
    corners = [SHEET_P0, SHEET_P3, SHEET_P2, SHEET_P1]
    uvs = [(0.0, 1.0), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]
    q = quad(corners, uvs)
    n = q["normals"][0]
    assert n[1] > 0.0 and n[2] < 0.0
    for p in (CAMERA_EYE, LIGHT_POS):
        assert sum(a * b for a, b in zip(n, sub(p, SHEET_P0))) < 0.0, "authored normal faces away"
    for p in corners:
        assert -1 < p[0] < 1 and 0 < p[1] < 2 and -1 < p[2] < 1, "sheet inside the room"
    return q


# ----------------------------------------------------------------------------------------------
# Materials (glTF metallic-roughness; extras carry the derived BRDF parameters as in cornell-a)
# ----------------------------------------------------------------------------------------------


def derived(base, metallic, roughness):
    return {
        "kd": [b * (1.0 - metallic) for b in base],
        "F0": [0.04 * (1.0 - metallic) + b * metallic for b in base],
        "ggx_alpha": roughness * roughness,
    }


def plain_material(name, base, metallic=0.0, roughness=1.0):
    return {
        "name": name,
        "pbrMetallicRoughness": {
            "baseColorFactor": list(base) + [1.0],
            "metallicFactor": metallic,
            "roughnessFactor": roughness,
        },
        "doubleSided": False,
        "extras": derived(base, metallic, roughness),
    }


# ----------------------------------------------------------------------------------------------
# Camera and light
# ----------------------------------------------------------------------------------------------
CAMERA_EYE = (0.0, 1.0, 3.4)
CAMERA_TARGET = (0.0, 1.0, 0.0)
CAMERA_YFOV_DEG = 40.0
IMAGE_W = IMAGE_H = 128
LIGHT_POS = (0.2, 1.75, 0.6)
LIGHT_INTENSITY = 4.0


def build():
    grey = (0.7, 0.7, 0.7)
    meshes = [
        # name, mesh, material
        ("floor", wall((-1.0, 0.0, 1.0), (2.0, 0.0, 0.0), (0.0, 0.0, -2.0), floor_uv), 0),
        ("ceiling", wall((-1.0, 2.0, -1.0), (2.0, 0.0, 0.0), (0.0, 0.0, 2.0)), 1),
        ("back", wall((-1.0, 0.0, -1.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0)), 2),
        ("left", wall((-1.0, 0.0, 1.0), (0.0, 0.0, -2.0), (0.0, 2.0, 0.0)), 3),
        ("right", wall((1.0, 0.0, -1.0), (0.0, 0.0, 2.0), (0.0, 2.0, 0.0)), 4),
        ("sheet", sheet(), 5),
    ]
    expected_normals = {"floor": (0, 1, 0), "ceiling": (0, -1, 0), "back": (0, 0, 1),
                        "left": (1, 0, 0), "right": (-1, 0, 0)}
    for name, m, _ in meshes:
        if name in expected_normals:
            assert all(abs(a - b) < 1e-12 for a, b in zip(m["normals"][0], expected_normals[name]))

    floor_mat = plain_material("floor_material", (0.8, 0.8, 0.8), 0.5, 0.4)
    floor_mat["normalTexture"] = {"index": 0, "texCoord": 0, "scale": 1.0}
    floor_mat["extras"]["normal_map"] = (
        "ridges_normal.png, tangent frame T = +x (dp/du), B = cross(N, T) * w = -z with w = +1 "
        "(towards decreasing v = image up), N = +y")
    sheet_mat = {
        "name": "sheet_material",
        "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 1.0, 1.0, 1.0],
            "baseColorTexture": {"index": 1, "texCoord": 0},
            "metallicFactor": 0.0,
            "roughnessFactor": 0.6,
        },
        "alphaMode": "MASK",
        "alphaCutoff": 0.5,
        "doubleSided": True,
        "extras": {
            "kd": "baseColorTexture RGB (sRGB-decoded) x (1 - metallic) = texture x 1",
            "F0": [0.04, 0.04, 0.04],
            "ggx_alpha": 0.36,
            "alpha_mask": "holes_color.png alpha (0 or 255 only) < 0.5 -> no surface",
        },
    }
    materials = [
        floor_mat,
        plain_material("ceiling_material", grey),
        plain_material("back_material", grey),
        plain_material("left_material", (0.7, 0.1, 0.1)),
        plain_material("right_material", (0.1, 0.7, 0.1)),
        sheet_mat,
    ]

    textures = {
        "textures": [{"name": "ridges_normal", "source": 0, "sampler": 0},
                     {"name": "holes_color", "source": 1, "sampler": 0}],
        # 9729 LINEAR for both mag and min (bilinear, no mipmaps: what the Mitsuba reference
        # does), 10497 REPEAT
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"name": "ridges_normal", "uri": "ridges_normal.png", "mimeType": "image/png"},
                   {"name": "holes_color", "uri": "holes_color.png", "mimeType": "image/png"}],
    }
    return pack_gltf(NAME, meshes, materials, textures)


def pack_gltf(name, meshes, materials, textures, extensions_used=()):
    """The glTF document and its binary buffer for `meshes` ((name, mesh, material index); a
    mesh may carry "tangents", VEC4), `materials`, `textures` (the textures / samplers / images
    entries), the module's camera and point light; one bufferView per accessor (as cornell-a)."""
    blob = bytearray()
    buffer_views, accessors = [], []

    def add(data, component_type, acc_type, count, target, minmax=None):
        while len(blob) % 4:
            blob.append(0)
        buffer_views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data),
                             "target": target})
        blob.extend(data)
        acc = {"bufferView": len(buffer_views) - 1, "byteOffset": 0,
               "componentType": component_type, "count": count, "type": acc_type}
        if minmax:
            acc["min"], acc["max"] = minmax
        accessors.append(acc)
        return len(accessors) - 1

    def f32(x):
        return struct.unpack("<f", struct.pack("<f", x))[0]

    def vec_accessor(vectors, acc_type, with_minmax):
        data = b"".join(struct.pack("<" + "f" * len(v), *v) for v in vectors)
        minmax = None
        if with_minmax:
            k = len(vectors[0])
            minmax = ([min(f32(v[c]) for v in vectors) for c in range(k)],
                      [max(f32(v[c]) for v in vectors) for c in range(k)])
        return add(data, 5126, acc_type, len(vectors), 34962, minmax)

    gltf_meshes = []
    for mesh_name, m, mat in meshes:
        attrs = {"POSITION": vec_accessor(m["positions"], "VEC3", True),
                 "NORMAL": vec_accessor(m["normals"], "VEC3", False)}
        if m.get("tangents") is not None:
            attrs["TANGENT"] = vec_accessor(m["tangents"], "VEC4", False)
        if m["uvs"] is not None:
            attrs["TEXCOORD_0"] = vec_accessor(m["uvs"], "VEC2", False)
        idx = add(struct.pack("<6I", *m["indices"]), 5125, "SCALAR", 6, 34963)
        gltf_meshes.append({"name": mesh_name, "primitives": [
            {"attributes": attrs, "indices": idx, "material": mat, "mode": 4}]})

    # Camera: forward = (0,0,-1) = the node's -z, up = +y: identity rotation.
    yfov = math.radians(CAMERA_YFOV_DEG)
    nodes = [{"name": mesh_name, "mesh": k} for k, (mesh_name, _, _) in enumerate(meshes)]
    nodes.append({"name": "camera", "camera": 0, "translation": list(CAMERA_EYE),
                  "rotation": [0.0, 0.0, 0.0, 1.0]})
    nodes.append({"name": "point_light", "translation": list(LIGHT_POS),
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})

    gltf = {
        "asset": {"version": "2.0", "generator": "scenes/%s/make_scene.py" % name,
                  "extras": {"units": "lengths in m; point light intensity = radiant intensity "
                                      "in W/sr per RGB channel (NOT candela)"}},
        "extensionsUsed": ["KHR_lights_punctual"] + list(extensions_used),
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "point_light", "type": "point", "color": [1.0, 1.0, 1.0],
             "intensity": LIGHT_INTENSITY}]}},
        "scene": 0,
        "scenes": [{"name": name, "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "camera", "type": "perspective",
                     "perspective": {"yfov": yfov, "aspectRatio": IMAGE_W / IMAGE_H,
                                     "znear": 0.01, "zfar": 100.0},
                     "extras": {"width": IMAGE_W, "height": IMAGE_H,
                                "yfov_deg": CAMERA_YFOV_DEG, "target": list(CAMERA_TARGET),
                                "up": [0.0, 1.0, 0.0]}}],
        "meshes": gltf_meshes,
        "materials": materials,
    }
    gltf.update(textures)
    gltf.update({
        "accessors": accessors,
        "bufferViews": buffer_views,
        "buffers": [{"uri": name + ".bin", "byteLength": len(blob)}],
    })
    return gltf, bytes(blob)


def write_gltf(directory, name, gltf, blob):
    """Writes `name`.gltf (JSON, indent 1, LF) and `name`.bin into `directory`."""
    with open(os.path.join(directory, name + ".gltf"), "w", encoding="utf-8", newline="\n") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")
    with open(os.path.join(directory, name + ".bin"), "wb") as f:
        f.write(blob)


def main():
    gltf, blob = build()
    write_gltf(HERE, NAME, gltf, blob)
    with open(os.path.join(HERE, "ridges_normal.png"), "wb") as f:
        f.write(png_bytes(TEX_N, TEX_N, ridges_rows(), 3))
    with open(os.path.join(HERE, "holes_color.png"), "wb") as f:
        f.write(png_bytes(TEX_N, TEX_N, holes_rows(), 4))
    print("wrote %s.gltf, %s.bin (%d B), ridges_normal.png, holes_color.png; ridge A = %.6f texels"
          % (NAME, NAME, len(blob), RIDGE_A))


if __name__ == "__main__":
    main()
