#!/usr/bin/env python3
"""Checks the conventions the materials reference relies on (results: reference/README.md).

(a) UV -> bitmap row: Mitsuba's bitmap texture at uv = (u, v) reads column u W, row v H with
    row 0 = the image's top row, i.e. glTF's convention (uv (0,0) = top-left); glTF TEXCOORD_0
    can be given to mi.Mesh unchanged.
(b) Normal-map frame: on the real floor (hit by rays from Mitsuba's scene), the world-space
    shading normal that Mitsuba's `normalmap` hands to the nested BSDF equals the glTF one,
    normalize(n.x T + n.y B + n.z N) with T = +x, B = cross(N, T) * w = -z (w = +1), N = +y and
    n = 2 * bilinear(texels / 255) - 1 computed here independently from the PNG.
(c) Mask edges: the fraction of the sheet's area where "bilinear alpha >= 0.5" and "nearest
    alpha >= 0.5" disagree.
(d) How much of the visible floor is seen from BELOW its shading normal (camera direction
    wi . n_s <= 0: zero radiance with the one-sided BRDF), and the smallest light-side cosine.

Usage: python tools/mitsuba/check_conventions.py
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import render_reference as rr  # noqa: E402
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

SCENE = os.path.join(HERE, "..", "..", "scenes", "materials")
GLTF = os.path.join(SCENE, "materials.gltf")
NORMAL_PNG = os.path.join(SCENE, "ridges_normal.png")
HOLES_PNG = os.path.join(SCENE, "holes_color.png")


def check_uv_rows():
    # 2 x 2 tensor: row 0 = red, green; row 1 = blue, white
    t = mi.TensorXf(dr.llvm.ad.Float([1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1]), shape=(2, 2, 3))
    tex = mi.load_dict({"type": "bitmap", "raw": True, "filter_type": "nearest", "data": t})
    uvs = [(0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)]
    si = dr.zeros(mi.SurfaceInteraction3f, 4)
    si.uv = mi.Point2f(dr.llvm.ad.Float([u for u, _ in uvs]), dr.llvm.ad.Float([v for _, v in uvs]))
    c = tex.eval(si)
    got = [(round(c[0][k]), round(c[1][k]), round(c[2][k])) for k in range(4)]
    expected = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)]
    print("(a) uv -> texel:", list(zip(uvs, got)), "OK" if got == expected else "MISMATCH")
    return got == expected


class Probe(mi.BSDF):
    """Returns one vector of the (world-space) shading frame it is evaluated with."""

    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.which = props["which"]
        self.m_components = [mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide]
        self.m_flags = self.m_components[0]

    def eval(self, ctx, si, wo, active=True):
        v = {"n": si.sh_frame.n, "s": si.sh_frame.s, "t": si.sh_frame.t}[self.which]
        return mi.Color3f(v.x, v.y, v.z)

    def traverse(self, cb):
        pass

    def to_string(self):
        return "Probe"


mi.register_bsdf("frame_probe", lambda p: Probe(p))

_PNG_CACHE = {}


def png(path):
    if path not in _PNG_CACHE:
        _PNG_CACHE[path] = rr.read_png(path)
    return _PNG_CACHE[path]


def bilinear(path, u, v, c):
    """GL-style bilinear lookup (texel centres at (i + 0.5) / W, repeat) of channel c, in [0,1]."""
    w, h, nc, rows = png(path)
    x, y = u * w - 0.5, v * h - 0.5
    i0, j0 = math.floor(x), math.floor(y)
    fx, fy = x - i0, y - j0

    def t(i, j):
        return rows[j % h][(i % w) * nc + c] / 255.0
    return ((1 - fx) * (1 - fy) * t(i0, j0) + fx * (1 - fy) * t(i0 + 1, j0)
            + (1 - fx) * fy * t(i0, j0 + 1) + fx * fy * t(i0 + 1, j0 + 1))


def nearest(path, u, v, c):
    w, h, nc, rows = png(path)
    return rows[math.floor(v * h) % h][(math.floor(u * w) % w) * nc + c] / 255.0


def gltf_floor_normal(x, z, flip_b=False):
    u, v = 2.0 * (x + 1.0), 2.0 * (z + 1.0)
    n = [2.0 * bilinear(NORMAL_PNG, u, v, c) - 1.0 for c in range(3)]
    T, B, N = (1.0, 0.0, 0.0), (0.0, 0.0, -1.0 if not flip_b else 1.0), (0.0, 1.0, 0.0)
    wn = [n[0] * T[k] + n[1] * B[k] + n[2] * N[k] for k in range(3)]
    length = math.sqrt(sum(a * a for a in wn))
    return [a / length for a in wn]


def check_floor_frame():
    g = rr.Gltf(GLTF)
    scene, _, _ = rr.build_scene(g, 128, 128, 1, 2, "bilinear")
    # a 9 x 9 grid of points on the floor, hit from above
    xs, zs = [], []
    for a in range(9):
        for b in range(9):
            xs.append(-0.93 + 0.22 * a + 0.0123 * b)
            zs.append(-0.95 + 0.22 * b + 0.0071 * a)
    n = len(xs)
    o = mi.Point3f(dr.llvm.ad.Float(xs), dr.llvm.ad.Float([0.3] * n), dr.llvm.ad.Float(zs))
    si = scene.ray_intersect(mi.Ray3f(o, mi.Vector3f(0, -1, 0)))
    print("(b) Mitsuba at the floor: dp_du =", [si.dp_du.x[0], si.dp_du.y[0], si.dp_du.z[0]],
          "dp_dv =", [si.dp_dv.x[0], si.dp_dv.y[0], si.dp_dv.z[0]],
          "sh_frame s =", [si.sh_frame.s.x[0], si.sh_frame.s.y[0], si.sh_frame.s.z[0]],
          "t =", [si.sh_frame.t.x[0], si.sh_frame.t.y[0], si.sh_frame.t.z[0]])
    b = mi.load_dict({
        "type": "normalmap", "flip_invalid_normals": False, "use_shadowing_function": False,
        "normalmap": {"type": "bitmap", "raw": True, "filter_type": "bilinear", "wrap_mode": "repeat",
                      "data": rr.texture_tensor(NORMAL_PNG, (0, 1, 2), lambda x: x)},
        "nested": {"type": "frame_probe", "which": "n"}})
    si.wi = mi.Vector3f(0, 0, 1)
    mn = b.eval(mi.BSDFContext(), si, mi.Vector3f(0, 0, 1))
    worst, worst_flip = 0.0, 0.0
    for k in range(n):
        m = [mn[0][k], mn[1][k], mn[2][k]]
        worst = max(worst, max(abs(p - q) for p, q in zip(m, gltf_floor_normal(xs[k], zs[k]))))
        worst_flip = max(worst_flip, max(abs(p - q) for p, q in
                                         zip(m, gltf_floor_normal(xs[k], zs[k], True))))
    ok = worst < 1e-5
    print("(b) max |n_mitsuba - n_glTF(T=+x, B=-z)| over %d floor points = %.2e; with B = +z "
          "instead: %.3f  %s" % (n, worst, worst_flip, "OK" if ok else "MISMATCH"))
    return ok


def check_mask_edges(steps=512):
    differ = 0
    for a in range(steps):
        for b in range(steps):
            u, v = (a + 0.5) / steps, (b + 0.5) / steps
            bil = bilinear(HOLES_PNG, u, v, 3) >= 0.5
            nea = nearest(HOLES_PNG, u, v, 3) >= 0.5
            differ += bil != nea
    frac_holes = sum(1 for a in range(steps) for b in range(steps)
                     if bilinear(HOLES_PNG, (a + 0.5) / steps, (b + 0.5) / steps, 3) < 0.5) / steps ** 2
    print("(c) sheet area: holes (bilinear alpha < 0.5) %.4f; bilinear vs nearest cutoff differ "
          "on %.4f of the area" % (frac_holes, differ / steps ** 2))


def check_backfacing(res=128):
    """Pixel-centre camera rays that hit the floor: fraction with wi . n_s <= 0."""
    g = rr.Gltf(GLTF)
    cam = g.camera()
    light = g.point_lights()[0]["position"]
    t = math.tan(cam["yfov"] / 2.0)
    eye = cam["eye"]
    hits = back = 0
    min_cos_light = 1.0
    for j in range(res):
        for i in range(res):
            x = (2.0 * (i + 0.5) / res - 1.0) * t
            y = (1.0 - 2.0 * (j + 0.5) / res) * t
            d = (x, y, -1.0)  # forward = -z, right = +x, up = +y
            if d[1] >= 0:
                continue
            s = -eye[1] / d[1]
            p = (eye[0] + s * d[0], 0.0, eye[2] + s * d[2])
            if not (-1 <= p[0] <= 1 and -1 <= p[2] <= 1):
                continue
            # the sheet may hide the floor; only count the floor's own geometry (upper bound)
            hits += 1
            n = gltf_floor_normal(p[0], p[2])
            wi = [-c for c in d]
            if sum(a * b for a, b in zip(wi, n)) <= 0.0:
                back += 1
            lv = [light[k] - p[k] for k in range(3)]
            ll = math.sqrt(sum(c * c for c in lv))
            min_cos_light = min(min_cos_light, sum(n[k] * lv[k] for k in range(3)) / ll)
    print("(d) floor pixel centres (ignoring occlusion by the sheet): %d, seen from below the "
          "shading normal: %d (%.1f %%); smallest cos(n_s, light) = %.3f"
          % (hits, back, 100.0 * back / hits, min_cos_light))


if __name__ == "__main__":
    check_uv_rows()
    check_floor_frame()
    check_mask_edges()
    check_backfacing()
