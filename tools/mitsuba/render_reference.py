#!/usr/bin/env python3
"""Independent Mitsuba 3 reference renders (direct / one-bounce indirect / total) of a glTF scene.

Reads the glTF JSON and its .bin / PNG files directly (own parser, no glTF library), builds the
Mitsuba scene from the SAME float32 triangles, and renders it in passes:

    direct   = volpath max_depth=2 (light -> surface -> camera)
    total    = volpath max_depth=3 (direct + exactly one indirect bounce)
    indirect = total - direct     (pass k uses seed first_seed + k in BOTH renders, so the
                                   camera / first-bounce random numbers are identical and the
                                   direct part cancels pass by pass)

Per-pixel standard errors come from the spread of the passes. Outputs (into --out):
direct/total/indirect(.exr, _stderr.exr), direct/total/indirect.png (sRGB, clamped),
render_stats.json.

Scene conventions (see scenes/materials/reference/README.md):
  * every material: the `diffuse_ggx` BSDF (diffuse_ggx.py) with kd = baseColor (x texture,
    sRGB-decoded) x (1 - metallic), f0 = 0.04 (1 - metallic) + baseColor metallic,
    alpha = roughness^2;
  * normalTexture: Mitsuba `normalmap` around the BSDF, the map as a raw (linear) bilinear,
    repeating bitmap; flip_invalid_normals=false and use_shadowing_function=false (plain
    normal mapping; Mitsuba's defaults would alter the shading);
  * doubleSided: `twosided` around the BSDF (the same BRDF on both sides, the back side's
    shading normal = -N);
  * alphaMode MASK: `mask` around everything, its opacity = 1 if the bilinearly filtered alpha
    >= alphaCutoff else 0 (a Python texture, `CutoffTexture`; --mask-filter nearest uses a
    nearest-neighbour lookup instead);
  * KHR_lights_punctual point light: Mitsuba `point`, intensity = glTF intensity x colour in
    W/sr per channel; a hard-edged spot light (innerConeAngle = outerConeAngle): Mitsuba
    `spot` with cutoff_angle = beam_width = the cone's angle (a smooth glTF falloff is refused:
    Mitsuba's ramp is linear in the angle);
  * camera: `perspective`, fov_axis 'y', fov = yfov in degrees, box pixel filter.

The integrator is `volpath`, not `path`: Mitsuba's `path` treats `mask` cut-outs as opaque for
shadow rays and counts passing through a cut-out as a bounce (max_depth), `volpath` does neither
(null interactions are skipped and shadow rays are attenuated by the null transmission).

Usage (from the repository root):
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
    python tools/mitsuba/render_reference.py scenes/materials/materials.gltf \\
        --out scenes/materials/reference --passes 128 --pass-spp 256
"""
import argparse
import glob
import json
import math
import os
import struct
import sys
import time
import zlib


def _pick_llvm():
    """drjit needs a recent libLLVM (LLVM 14/15 fail with 'Cannot select: fminimum')."""
    if "DRJIT_LIBLLVM_PATH" in os.environ:
        return
    found = []
    for p in glob.glob("/usr/lib/x86_64-linux-gnu/libLLVM-*.so*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"):
        digits = "".join(c if c.isdigit() else " " for c in os.path.basename(p)).split()
        if digits:
            found.append((int(digits[0]), p))
    if found:
        os.environ["DRJIT_LIBLLVM_PATH"] = max(found)[1]


_pick_llvm()
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

mi.set_variant("llvm_ad_rgb")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import diffuse_ggx  # noqa: E402

diffuse_ggx.register()


# ==============================================================================================
# PNG decoding (8-bit, non-interlaced; grey, grey+alpha, RGB, RGBA; all five row filters)
# ==============================================================================================

def read_png(path):
    """Returns (width, height, channels, rows) with rows[j] a bytes object, row 0 = the top."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        tag = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if tag == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        elif tag == b"IEND":
            break
    width, height, depth, color_type, _, _, interlace = ihdr
    assert depth == 8 and interlace == 0, "only 8-bit non-interlaced PNGs are supported"
    channels = {0: 1, 4: 2, 2: 3, 6: 4}[color_type]
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for j in range(height):
        f = raw[j * (stride + 1)]
        line = bytearray(raw[j * (stride + 1) + 1:(j + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                line[x] = (line[x] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, channels, rows


def srgb_to_linear(c):
    """The sRGB transfer function's inverse (IEC 61966-2-1), c in [0, 1]."""
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def texture_tensor(path, channels, transform):
    """A float32 H x W x len(channels) tensor (row 0 = the image's top row) of
    transform(byte / 255) for the given channel indices of the PNG."""
    w, h, nc, rows = read_png(path)
    values = []
    for j in range(h):
        r = rows[j]
        for i in range(w):
            for c in channels:
                values.append(transform(r[i * nc + c] / 255.0))
    return mi.TensorXf(dr.llvm.ad.Float(values), shape=(h, w, len(channels)))


# ==============================================================================================
# The alpha-cutoff opacity texture: 1 where the (bilinear or nearest) alpha >= cutoff, else 0
# ==============================================================================================

class CutoffTexture(mi.Texture):
    def __init__(self, props):
        mi.Texture.__init__(self, props)
        self.inner = props["inner"]  # a 1-channel bitmap texture of alpha in [0, 1]
        self.cutoff = float(props["cutoff"])

    def eval_1(self, si, active=True):
        return dr.select(self.inner.eval_1(si, active) >= self.cutoff, mi.Float(1.0), mi.Float(0.0))

    def eval(self, si, active=True):
        return mi.Color3f(self.eval_1(si, active))

    def eval_3(self, si, active=True):
        return mi.Color3f(self.eval_1(si, active))

    def mean(self):
        return self.inner.mean()

    def is_spatially_varying(self):
        return True

    def traverse(self, callback):
        pass

    def to_string(self):
        return "CutoffTexture[cutoff=%g, inner=%s]" % (self.cutoff, self.inner)


mi.register_texture("alpha_cutoff", lambda props: CutoffTexture(props))


# ==============================================================================================
# glTF reading
# ==============================================================================================

COMPONENT = {5126: ("f", 4), 5125: ("I", 4), 5123: ("H", 2), 5121: ("B", 1)}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def quat_rotate(q, v):
    x, y, z, w = q
    # v' = v + 2 w (q x v) + 2 q x (q x v)
    qv = (x, y, z)

    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    t = tuple(2.0 * c for c in cross(qv, v))
    u = cross(qv, t)
    return tuple(v[k] + w * t[k] + u[k] for k in range(3))


class Gltf:
    def __init__(self, path):
        self.path = path
        self.base = os.path.dirname(os.path.abspath(path))
        self.doc = json.load(open(path, encoding="utf-8"))
        self.buffers = [open(os.path.join(self.base, b["uri"]), "rb").read()
                        for b in self.doc["buffers"]]
        for b, data in zip(self.doc["buffers"], self.buffers):
            assert len(data) == b["byteLength"], "buffer length mismatch"

    def accessor(self, index):
        """A flat list of the accessor's components (float32 read exactly, as Python floats)."""
        acc = self.doc["accessors"][index]
        bv = self.doc["bufferViews"][acc["bufferView"]]
        fmt, size = COMPONENT[acc["componentType"]]
        n = NCOMP[acc["type"]]
        stride = bv.get("byteStride", size * n)
        start = bv.get("byteOffset", 0) + acc.get("byteOffset", 0)
        data = self.buffers[bv["buffer"]]
        out = []
        for k in range(acc["count"]):
            out.extend(struct.unpack_from("<%d%s" % (n, fmt), data, start + k * stride))
        return out

    def mesh_nodes(self):
        """(node name, mesh index) for every mesh node; mesh nodes must have no transform."""
        scene = self.doc["scenes"][self.doc.get("scene", 0)]
        out = []
        stack = list(scene["nodes"])
        while stack:
            ni = stack.pop(0)
            node = self.doc["nodes"][ni]
            if "mesh" in node:
                for key in ("matrix", "translation", "rotation", "scale"):
                    assert key not in node, "mesh node '%s' has a transform" % node.get("name")
                out.append((node.get("name", "node%d" % ni), node["mesh"]))
            stack.extend(node.get("children", []))
        return out

    def camera(self):
        for node in self.doc["nodes"]:
            if "camera" in node:
                cam = self.doc["cameras"][node["camera"]]
                q = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
                eye = tuple(node.get("translation", [0.0, 0.0, 0.0]))
                forward = quat_rotate(q, (0.0, 0.0, -1.0))
                up = quat_rotate(q, (0.0, 1.0, 0.0))
                extras = cam.get("extras", {})
                return {"eye": eye, "forward": forward, "up": up,
                        "yfov": cam["perspective"]["yfov"],
                        "aspect": cam["perspective"].get("aspectRatio", 1.0),
                        "width": extras.get("width", 256), "height": extras.get("height", 256)}
        raise ValueError("no camera")

    def lights(self):
        """Point lights, and spot lights with a hard edge (innerConeAngle = outerConeAngle:
        Mitsuba's spot falls off linearly in the angle, glTF's as the squared cosine ramp, so
        only the hard edge is the same light in both)."""
        lights = self.doc["extensions"]["KHR_lights_punctual"]["lights"]
        out = []
        for node in self.doc["nodes"]:
            ext = node.get("extensions", {}).get("KHR_lights_punctual")
            if ext is None:
                continue
            light = lights[ext["light"]]
            assert light["type"] in ("point", "spot")
            assert "scale" not in node and "matrix" not in node
            color = light.get("color", [1.0, 1.0, 1.0])
            intensity = light.get("intensity", 1.0)
            found = {"type": light["type"], "position": tuple(node["translation"]),
                     "intensity": [intensity * c for c in color]}
            if light["type"] == "spot":
                spot = light.get("spot", {})
                outer = spot.get("outerConeAngle", math.pi / 4.0)
                assert spot.get("innerConeAngle", 0.0) == outer, "only hard-edged spots"
                found["direction"] = quat_rotate(node.get("rotation", [0, 0, 0, 1]), (0.0, 0.0, -1.0))
                found["cone_deg"] = math.degrees(outer)
            else:
                assert "rotation" not in node
            out.append(found)
        return out

    def image_path(self, texture_index):
        tex = self.doc["textures"][texture_index]
        if "sampler" in tex:
            s = self.doc["samplers"][tex["sampler"]]
            # the reference implements bilinear filtering without mipmaps and REPEAT wrapping
            assert s.get("wrapS", 10497) == 10497 and s.get("wrapT", 10497) == 10497
        return os.path.join(self.base, self.doc["images"][tex["source"]]["uri"])


# ==============================================================================================
# Mitsuba scene
# ==============================================================================================

def material_bsdf(g, mat, mask_filter):
    """The Mitsuba BSDF of a glTF material (see the module docstring)."""
    pbr = mat.get("pbrMetallicRoughness", {})
    base = pbr.get("baseColorFactor", [1.0, 1.0, 1.0, 1.0])
    metallic = pbr.get("metallicFactor", 1.0)
    roughness = pbr.get("roughnessFactor", 1.0)
    assert "metallicRoughnessTexture" not in pbr and "emissiveTexture" not in mat
    f0 = [0.04 * (1.0 - metallic) + b * metallic for b in base[:3]]
    alpha = roughness * roughness
    tex_info = pbr.get("baseColorTexture")
    if tex_info is not None:
        assert tex_info.get("texCoord", 0) == 0
        path = g.image_path(tex_info["index"])
        scale = [b * (1.0 - metallic) for b in base[:3]]
        # kd = sRGB-decoded texel x factor x (1 - metallic), bilinearly interpolated in linear
        # space; the factor is folded into the texels (exact: interpolation is linear).
        w, h, nc, rows = read_png(path)
        vals = []
        for j in range(h):
            for i in range(w):
                for c in range(3):
                    vals.append(srgb_to_linear(rows[j][i * nc + c] / 255.0) * scale[c])
        kd = {"type": "bitmap", "raw": True, "filter_type": "bilinear", "wrap_mode": "repeat",
              "data": mi.TensorXf(dr.llvm.ad.Float(vals), shape=(h, w, 3))}
    else:
        kd = {"type": "rgb", "value": [b * (1.0 - metallic) for b in base[:3]]}
    bsdf = {"type": "diffuse_ggx", "kd": kd, "f0": f0, "alpha": alpha}
    aniso = mat.get("extensions", {}).get("KHR_materials_anisotropy")
    if aniso is not None:
        assert "anisotropyTexture" not in aniso
        strength = aniso.get("anisotropyStrength", 0.0)
        # KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2) along
        # cos(rotation) T + sin(rotation) B; T = dp/du and B = cross(N, T) are Mitsuba's s and
        # t where the tangent frame has w = +1 (checked in build_scene).
        bsdf["alpha_t"] = alpha + (1.0 - alpha) * strength * strength
        bsdf["rotation"] = aniso.get("anisotropyRotation", 0.0)

    normal_info = mat.get("normalTexture")
    if normal_info is not None:
        assert normal_info.get("texCoord", 0) == 0 and normal_info.get("scale", 1.0) == 1.0
        nmap = texture_tensor(g.image_path(normal_info["index"]), (0, 1, 2), lambda x: x)
        bsdf = {"type": "normalmap",
                "normalmap": {"type": "bitmap", "raw": True, "filter_type": "bilinear",
                              "wrap_mode": "repeat", "data": nmap},
                "flip_invalid_normals": False, "use_shadowing_function": False,
                "nested": bsdf}

    if mat.get("doubleSided", False):
        bsdf = {"type": "twosided", "nested": bsdf}

    mode = mat.get("alphaMode", "OPAQUE")
    if mode == "MASK":
        assert tex_info is not None
        cutoff = mat.get("alphaCutoff", 0.5)
        path = g.image_path(tex_info["index"])
        _, _, nc, _ = read_png(path)
        assert nc in (2, 4)
        # alpha = texel alpha x baseColorFactor alpha
        a_tensor = texture_tensor(path, (nc - 1,), lambda x: x * base[3])
        inner = mi.load_dict({"type": "bitmap", "raw": True, "filter_type": mask_filter,
                              "wrap_mode": "repeat", "data": a_tensor})
        bsdf = {"type": "mask",
                "opacity": {"type": "alpha_cutoff", "inner": inner, "cutoff": cutoff},
                "nested": bsdf}
    else:
        assert mode == "OPAQUE", mode
    return mi.load_dict(bsdf)


def check_tangents(tangents, pos, nrm, uv, idx):
    """Stored glTF tangents must be what Mitsuba uses: T = normalize(dp/du) (made orthogonal to
    N) with w = +1, i.e. B = cross(N, T) points towards decreasing v, per triangle."""
    def vec(a, k, n):
        return a[n * k:n * k + n]
    for f in range(len(idx) // 3):
        i0, i1, i2 = idx[3 * f:3 * f + 3]
        p0, p1, p2 = (vec(pos, i, 3) for i in (i0, i1, i2))
        t0, t1, t2 = (vec(uv, i, 2) for i in (i0, i1, i2))
        e1 = [a - b for a, b in zip(p1, p0)]
        e2 = [a - b for a, b in zip(p2, p0)]
        du1, dv1 = t1[0] - t0[0], t1[1] - t0[1]
        du2, dv2 = t2[0] - t0[0], t2[1] - t0[1]
        det = du1 * dv2 - du2 * dv1
        dpdu = [(dv2 * a - dv1 * b) / det for a, b in zip(e1, e2)]
        dpdv = [(du1 * b - du2 * a) / det for a, b in zip(e1, e2)]
        for i in (i0, i1, i2):
            t = vec(tangents, i, 4)
            n = vec(nrm, i, 3)
            length = math.sqrt(sum(c * c for c in dpdu))
            assert max(abs(a - b / length) for a, b in zip(t[:3], dpdu)) < 1e-6, (t, dpdu)
            b = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
            assert t[3] == 1.0 and sum(x * y for x, y in zip(b, dpdv)) < 0.0, "w = +1 needed"


def build_scene(g, width, height, pass_spp, max_depth, mask_filter):
    shapes = {}
    triangles = 0
    for name, mesh_index in g.mesh_nodes():
        for pi, prim in enumerate(g.doc["meshes"][mesh_index]["primitives"]):
            assert prim.get("mode", 4) == 4
            pos = g.accessor(prim["attributes"]["POSITION"])
            nrm = g.accessor(prim["attributes"]["NORMAL"])
            uv = g.accessor(prim["attributes"]["TEXCOORD_0"]) if "TEXCOORD_0" in prim["attributes"] else None
            idx = g.accessor(prim["indices"])
            nv, nf = len(pos) // 3, len(idx) // 3
            if "TANGENT" in prim["attributes"]:
                check_tangents(g.accessor(prim["attributes"]["TANGENT"]), pos, nrm, uv, idx)
            props = mi.Properties()
            props["bsdf"] = material_bsdf(g, g.doc["materials"][prim["material"]], mask_filter)
            mesh = mi.Mesh("%s_%d" % (name, pi), nv, nf, props=props,
                           has_vertex_normals=True, has_vertex_texcoords=uv is not None)
            params = mi.traverse(mesh)
            params["vertex_positions"] = dr.llvm.ad.Float(pos)
            params["vertex_normals"] = dr.llvm.ad.Float(nrm)
            if uv is not None:
                params["vertex_texcoords"] = dr.llvm.ad.Float(uv)
            params["faces"] = dr.llvm.ad.UInt(idx)
            params.update()
            shapes["%s_%d" % (name, pi)] = mesh
            triangles += nf

    cam = g.camera()
    eye = cam["eye"]
    target = tuple(e + f for e, f in zip(eye, cam["forward"]))
    scene = {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": max_depth, "rr_depth": 1000,
                       "hide_emitters": False},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": math.degrees(cam["yfov"]),
            "near_clip": 0.01, "far_clip": 100.0,
            "to_world": mi.ScalarTransform4f().look_at(origin=list(eye), target=list(target),
                                                       up=list(cam["up"])),
            "sampler": {"type": "independent", "sample_count": pass_spp},
            "film": {"type": "hdrfilm", "width": width, "height": height,
                     "rfilter": {"type": "box"}, "pixel_format": "rgb",
                     "component_format": "float32"},
        },
    }
    for k, light in enumerate(g.lights()):
        intensity = {"type": "rgb", "value": light["intensity"]}
        if light["type"] == "point":
            scene["light%d" % k] = {"type": "point", "position": list(light["position"]),
                                    "intensity": intensity}
        else:
            p, d = light["position"], light["direction"]
            up = [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0]
            scene["light%d" % k] = {
                "type": "spot", "intensity": intensity,
                "cutoff_angle": light["cone_deg"], "beam_width": light["cone_deg"],
                "to_world": mi.ScalarTransform4f().look_at(
                    origin=list(p), target=[p[i] + d[i] for i in range(3)], up=up)}
    scene.update(shapes)
    return mi.load_dict(scene), triangles, cam


def camera_ray_check(scene, cam, width, height):
    """Largest |d_mitsuba - d_formula| over a few sub-pixel positions (the pinhole formula of
    the reference README)."""
    sensor = scene.sensors()[0]
    t = math.tan(cam["yfov"] / 2.0)
    aspect = width / height
    f = cam["forward"]
    up = cam["up"]
    right = (f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0])
    worst = 0.0
    for (i, j, s, tt) in [(0, 0, 0.0, 0.0), (5, 17, 0.3, 0.7), (width - 1, height - 1, 0.99, 0.99),
                          (width // 2, height // 3, 0.5, 0.5), (width - 3, 2, 0.1, 0.9)]:
        x = (2.0 * (i + s) / width - 1.0) * aspect * t
        y = (1.0 - 2.0 * (j + tt) / height) * t
        d = [f[k] + x * right[k] + y * up[k] for k in range(3)]
        n = math.sqrt(sum(c * c for c in d))
        d = [c / n for c in d]
        ray, _ = sensor.sample_ray(0.0, 0.5, mi.Point2f((i + s) / width, (j + tt) / height),
                                   mi.Point2f(0.5, 0.5))
        md = [ray.d.x[0], ray.d.y[0], ray.d.z[0]]
        worst = max(worst, max(abs(a - b) for a, b in zip(md, d)))
    return worst


# ==============================================================================================
# Statistics and output
# ==============================================================================================

Float64 = dr.llvm.ad.Float64


def write_exr(path, values, width, height):
    t = mi.TensorXf(dr.llvm.ad.Float(values), shape=(height, width, 3))
    mi.Bitmap(t, pixel_format=mi.Bitmap.PixelFormat.RGB).write(path)


def write_png(path, values, width, height):
    t = mi.TensorXf(dr.llvm.ad.Float(values), shape=(height, width, 3))
    mi.util.convert_to_bitmap(t).write(path)


def percentile(sorted_values, p):
    if not sorted_values:
        return float("nan")
    k = (len(sorted_values) - 1) * p
    lo = int(math.floor(k))
    hi = min(lo + 1, len(sorted_values) - 1)
    return sorted_values[lo] + (sorted_values[hi] - sorted_values[lo]) * (k - lo)


def image_stats(mean, se, width, height):
    n = width * height
    out = {}
    out["mean_rgb"] = [round(sum(mean[c::3]) / n, 6) for c in range(3)]
    # standard error of the image mean from per-pixel errors (pixels independent)
    out["mean_rgb_stderr"] = [float("%.3g" % (math.sqrt(sum(s * s for s in se[c::3])) / n))
                              for c in range(3)]
    out["min"] = min(mean)
    out["max"] = max(mean)
    out["nonfinite"] = sum(1 for v in mean if not math.isfinite(v))
    gray_rel, chan_rel = [], []
    zero_px = 0
    for p in range(n):
        v = mean[3 * p:3 * p + 3]
        s = se[3 * p:3 * p + 3]
        mv = sum(v) / 3.0
        if mv > 1e-6:
            gray_rel.append((sum(s) / 3.0) / mv)
        else:
            zero_px += 1
        for c in range(3):
            if v[c] > 1e-6:
                chan_rel.append(s[c] / v[c])
    gray_rel.sort()
    chan_rel.sort()
    out["pixels_zero_or_black"] = zero_px
    out["rel_se_px_gray_median"] = round(percentile(gray_rel, 0.5), 5)
    out["rel_se_px_gray_p90"] = round(percentile(gray_rel, 0.9), 5)
    out["rel_se_px_gray_p99"] = round(percentile(gray_rel, 0.99), 5)
    out["rel_se_channel_median"] = round(percentile(chan_rel, 0.5), 5)
    out["rel_se_channel_p99"] = round(percentile(chan_rel, 0.99), 5)
    out["frac_px_rel_gt_2pct"] = round(sum(1 for r in gray_rel if r > 0.02) / max(1, len(gray_rel)), 4)
    out["frac_px_rel_gt_5pct"] = round(sum(1 for r in gray_rel if r > 0.05) / max(1, len(gray_rel)), 4)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("gltf")
    ap.add_argument("--out", required=True)
    ap.add_argument("--passes", type=int, default=128)
    ap.add_argument("--pass-spp", type=int, default=256)
    ap.add_argument("--first-seed", type=int, default=0)
    ap.add_argument("--width", type=int, default=None, help="default: the camera's extras")
    ap.add_argument("--height", type=int, default=None)
    ap.add_argument("--mask-filter", choices=["bilinear", "nearest"], default="bilinear",
                    help="how the alpha texture is looked up before the cutoff")
    args = ap.parse_args()

    t_start = time.time()
    g = Gltf(args.gltf)
    cam0 = g.camera()
    width = args.width or cam0["width"]
    height = args.height or cam0["height"]
    os.makedirs(args.out, exist_ok=True)

    scenes = {}
    for key, depth in (("direct", 2), ("total", 3)):
        scenes[key], triangles, cam = build_scene(g, width, height, args.pass_spp, depth,
                                                  args.mask_filter)
    ray_diff = camera_ray_check(scenes["direct"], cam, width, height)
    print("scene: %d triangles, %dx%d, camera ray max |diff| = %.2e" % (triangles, width, height, ray_diff))

    n = width * height * 3
    acc = {k: [dr.zeros(Float64, n), dr.zeros(Float64, n)] for k in ("direct", "total", "indirect")}
    times = {"direct": 0.0, "total": 0.0}
    t_loop = time.time()
    for p in range(args.passes):
        seed = args.first_seed + p
        imgs = {}
        for key in ("direct", "total"):
            t0 = time.time()
            img = mi.render(scenes[key], seed=seed, spp=args.pass_spp)
            imgs[key] = Float64(dr.ravel(img))
            dr.eval(imgs[key])
            times[key] += time.time() - t0
        imgs["indirect"] = imgs["total"] - imgs["direct"]
        for key in acc:
            acc[key][0] += imgs[key]
            acc[key][1] += dr.square(imgs[key])
            dr.eval(acc[key])
        if p == 0 or (p + 1) % max(1, args.passes // 8) == 0:
            el = time.time() - t_loop
            print("pass %d/%d  %.1f s  (%.1f s/pass)" % (p + 1, args.passes, el, el / (p + 1)), flush=True)
    t_render = time.time() - t_loop

    P = args.passes
    stats = {
        "scene": os.path.splitext(os.path.basename(args.gltf))[0],
        "mitsuba": mi.__version__, "drjit": dr.__version__, "variant": mi.variant(),
        "integrator": "volpath (max_depth 2 = direct, 3 = total; rr_depth 1000)",
        "mask_filter": args.mask_filter,
        "spp": P * args.pass_spp, "pass_spp": args.pass_spp, "passes": P,
        "seed_first_pass": args.first_seed, "width": width, "height": height,
        "triangles": triangles,
        "time_direct_s": round(times["direct"], 2), "time_total_s": round(times["total"], 2),
        "time_render_s": round(t_render, 2),
        "ms_per_spp_direct": round(1000 * times["direct"] / (P * args.pass_spp), 3),
        "ms_per_spp_total": round(1000 * times["total"] / (P * args.pass_spp), 3),
        "camera_ray_max_abs_diff": ray_diff,
        "images": {},
    }
    for key in ("direct", "total", "indirect"):
        s, s2 = acc[key]
        mean = s / P
        var = dr.maximum((s2 - P * dr.square(mean)) / max(1, P - 1), 0.0)
        se = dr.sqrt(var / P)
        mean_l = [float(v) for v in mi.Float(mean)]
        se_l = [float(v) for v in mi.Float(se)]
        write_exr(os.path.join(args.out, key + ".exr"), mean_l, width, height)
        write_exr(os.path.join(args.out, key + "_stderr.exr"), se_l, width, height)
        write_png(os.path.join(args.out, key + ".png"), mean_l, width, height)
        stats["images"][key] = image_stats(mean_l, se_l, width, height)
        print(key, json.dumps(stats["images"][key]))
    stats["time_wall_incl_load_jit_s"] = round(time.time() - t_start, 2)
    with open(os.path.join(args.out, "render_stats.json"), "w") as f:
        json.dump(stats, f, indent=1)
        f.write("\n")
    print("wrote %s (%.1f s in total)" % (args.out, time.time() - t_start))


if __name__ == "__main__":
    main()
