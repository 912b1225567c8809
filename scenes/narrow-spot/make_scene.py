#!/usr/bin/env python3
"""Writes narrow-spot.gltf and narrow-spot.bin: a grey floor lit by a hard-edged spot light
of 1 degree (innerConeAngle = outerConeAngle), seen from straight above so the lit disk
(radius tan 1 deg = 0.01746 at 1 m) fills half the image. The reference folder beside this
file holds Mitsuba 3's direct image of it (tools/mitsuba/render_reference.py); the test
tests/reference_narrow_spot.rs holds slc's direct image to it: the cone's angle, its edge
and the light on the axis (a falloff that clamped cos inner - cos outer at 1e-3 left 1/3.3e3
of the light inside such a cone). Python 3 standard library only; deterministic.
"""
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
CONE = math.radians(1.0)
SIZE = 64
HALF_VIEW = 0.03  # half the floor width the camera sees
CAMERA_HEIGHT = 1.5
# Rotation by -90 degrees about +x: the node's -z (where spots and cameras look) becomes -y.
DOWN = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]


def main():
    positions = [(-1.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, -1.0), (-1.0, 0.0, -1.0)]
    normals = [(0.0, 1.0, 0.0)] * 4
    indices = [0, 1, 2, 0, 2, 3]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    blob += struct.pack("<6I", *indices)
    with open(os.path.join(HERE, "narrow-spot.bin"), "wb") as f:
        f.write(blob)
    yfov = 2.0 * math.atan(HALF_VIEW / CAMERA_HEIGHT)
    doc = {
        "asset": {"version": "2.0", "generator": "scenes/narrow-spot/make_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{
            "type": "spot", "name": "narrow", "intensity": 10.0, "color": [1.0, 1.0, 1.0],
            "spot": {"innerConeAngle": CONE, "outerConeAngle": CONE}}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "floor", "mesh": 0},
            {"name": "spot", "translation": [0.0, 1.0, 0.0], "rotation": DOWN,
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "camera", "camera": 0, "translation": [0.0, CAMERA_HEIGHT, 0.0],
             "rotation": DOWN},
        ],
        "cameras": [{"type": "perspective", "perspective": {
            "yfov": yfov, "aspectRatio": 1.0, "znear": 0.01, "zfar": 100.0},
            "extras": {"width": SIZE, "height": SIZE}}],
        "meshes": [{"name": "floor", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "grey", "pbrMetallicRoughness": {
            "baseColorFactor": [0.7, 0.7, 0.7, 1.0], "metallicFactor": 0.0,
            "roughnessFactor": 1.0}}],
        "buffers": [{"uri": "narrow-spot.bin", "byteLength": len(blob)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48},
            {"buffer": 0, "byteOffset": 96, "byteLength": 24},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR"},
        ],
    }
    with open(os.path.join(HERE, "narrow-spot.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
