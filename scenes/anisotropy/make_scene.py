#!/usr/bin/env python3
"""Generates the `anisotropy` test scene: glTF `KHR_materials_anisotropy` (anisotropic GGX) on a
brushed-metal floor (tangents NOT stored: a renderer must generate them) and on a brushed
panel whose tangents ARE stored, with its anisotropy rotated, in the Cornell-like room of
`scenes/materials` (same camera, light, walls and conventions; see reference/README.md).

Writes, beside this file (deterministic, byte-identical on every run):
  anisotropy.gltf   glTF 2.0 JSON (8 nodes: 6 meshes, camera; KHR_lights_punctual point light)
  anisotropy.bin    float32 POSITION / NORMAL / TANGENT (panel only) / TEXCOORD_0, uint32 indices

Pure Python 3 standard library. The room, the packing and the camera come from
scenes/materials/make_scene.py.

Anisotropy (KHR_materials_anisotropy): alpha = roughness^2 along the bitangent direction,
alpha_t = alpha + (1 - alpha) strength^2 along the anisotropy direction
cos(rotation) T + sin(rotation) B, where T = dp/du and B = cross(N, T) (w = +1 on both meshes:
v grows against B). Mitsuba's shading frame is s = normalize(dp/du - N (N . dp/du)),
t = cross(N, s): the same T and B.
"""
import importlib.util
import os

HERE = os.path.dirname(os.path.abspath(__file__))
NAME = "anisotropy"

_spec = importlib.util.spec_from_file_location(
    "materials_scene", os.path.join(HERE, "..", "materials", "make_scene.py"))
room = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(room)

# The panel: a quad facing the camera (+z) in front of the back wall, where the light's
# reflection towards the camera falls (the mirror point of the light seen from the eye lies
# at about (0.15, 1.55) on the plane z = PANEL_Z).
PANEL_Z = -0.4
PANEL_X = (-0.35, 0.55)
PANEL_Y = (0.7, 1.75)

FLOOR_ANISOTROPY = {"anisotropyStrength": 0.8, "anisotropyRotation": 0.0}
PANEL_ANISOTROPY = {"anisotropyStrength": 0.9, "anisotropyRotation": 0.7}


def panel():
    (x0, x1), (y0, y1) = PANEL_X, PANEL_Y
    corners = [(x0, y0, PANEL_Z), (x1, y0, PANEL_Z), (x1, y1, PANEL_Z), (x0, y1, PANEL_Z)]
    # u grows with +x, v grows downwards (-y): the image reads upright from the camera, and
    # B = cross(N, T) = cross(+z, +x) = +y points towards decreasing v (w = +1).
    uvs = [((p[0] - x0) / (x1 - x0), (y1 - p[1]) / (y1 - y0)) for p in corners]
    q = room.quad(corners, uvs)
    assert q["normals"][0] == (0.0, 0.0, 1.0)
    q["tangents"] = [(1.0, 0.0, 0.0, 1.0)] * 4
    return q


def anisotropic_material(name, base, roughness, anisotropy):
    m = room.plain_material(name, base, metallic=1.0, roughness=roughness)
    m["extensions"] = {"KHR_materials_anisotropy": dict(anisotropy)}
    alpha = roughness * roughness
    s = anisotropy["anisotropyStrength"]
    m["extras"]["ggx_alpha_t"] = alpha + (1.0 - alpha) * s * s
    m["extras"]["anisotropy_direction"] = (
        "cos(%g) T + sin(%g) B, T = dp/du, B = cross(N, T)"
        % (anisotropy["anisotropyRotation"], anisotropy["anisotropyRotation"]))
    return m


def build():
    grey = (0.7, 0.7, 0.7)
    meshes = [
        ("floor", room.wall((-1.0, 0.0, 1.0), (2.0, 0.0, 0.0), (0.0, 0.0, -2.0), room.floor_uv), 0),
        ("ceiling", room.wall((-1.0, 2.0, -1.0), (2.0, 0.0, 0.0), (0.0, 0.0, 2.0)), 1),
        ("back", room.wall((-1.0, 0.0, -1.0), (2.0, 0.0, 0.0), (0.0, 2.0, 0.0)), 2),
        ("left", room.wall((-1.0, 0.0, 1.0), (0.0, 0.0, -2.0), (0.0, 2.0, 0.0)), 3),
        ("right", room.wall((1.0, 0.0, -1.0), (0.0, 0.0, 2.0), (0.0, 2.0, 0.0)), 4),
        ("panel", panel(), 5),
    ]
    materials = [
        anisotropic_material("brushed_floor", (0.9, 0.75, 0.55), 0.3, FLOOR_ANISOTROPY),
        room.plain_material("ceiling_material", grey),
        room.plain_material("back_material", grey),
        room.plain_material("left_material", (0.7, 0.1, 0.1)),
        room.plain_material("right_material", (0.1, 0.7, 0.1)),
        anisotropic_material("brushed_panel", (0.8, 0.8, 0.85), 0.4, PANEL_ANISOTROPY),
    ]
    return room.pack_gltf(NAME, meshes, materials, {}, ["KHR_materials_anisotropy"])


def main():
    gltf, blob = build()
    room.write_gltf(HERE, NAME, gltf, blob)
    print("wrote %s.gltf, %s.bin (%d B)" % (NAME, NAME, len(blob)))


if __name__ == "__main__":
    main()
