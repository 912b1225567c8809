#!/usr/bin/env python3
"""Point values of the anisotropic BRDF from Mitsuba 3's own GGX (diffuse_ggx.py with
alpha_t, i.e. mi.MicrofacetDistribution(GGX, alpha_u, alpha_v) and its separable Smith G), for
slc's convention test (tests/reference_anisotropy.rs).

Each row: alpha (across the anisotropy direction), alpha_t (along it), rotation (radians, from
the frame's s = +x towards t = +z x s = +y), wi and wo in the local shading frame (n = +z), and
Mitsuba's f(wi, wo) cos(wo) for kd = 0, F0 = 1 (Schlick F = 1), evaluated through the BSDF
interface (si.wi = wi). Deterministic (a fixed LCG).

Usage (from the repository root):
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so \\
    python tools/mitsuba/brdf_table.py scenes/anisotropy/reference/brdf_table.json
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402


class Lcg:
    def __init__(self, seed):
        self.state = seed

    def uniform(self):
        self.state = (self.state * 6364136223846793005 + 1442695040888963407) % 2**64
        return ((self.state >> 11) + 0.5) / 2**53


def above(rng, min_cos):
    """A direction of the upper hemisphere with cos >= min_cos."""
    cos = min_cos + (1.0 - min_cos) * rng.uniform()
    phi = 2.0 * math.pi * rng.uniform()
    sin = math.sqrt(max(0.0, 1.0 - cos * cos))
    return [sin * math.cos(phi), sin * math.sin(phi), cos]


def main():
    out = sys.argv[1]
    mi.set_variant("llvm_ad_rgb")
    import diffuse_ggx
    diffuse_ggx.register()
    rng = Lcg(2026)
    rows = []
    for alpha, alpha_t, rotation in [(0.09, 0.6724, 0.0), (0.16, 0.8404, 0.7),
                                     (0.3, 0.05, -1.2), (0.02, 0.5, 2.5), (0.5, 0.5, 0.3)]:
        bsdf = mi.load_dict({"type": "diffuse_ggx", "kd": [0.0, 0.0, 0.0],
                             "f0": [1.0, 1.0, 1.0], "alpha": alpha, "alpha_t": alpha_t,
                             "rotation": rotation})
        for k in range(60):
            wi = above(rng, 0.05)
            if k % 2 == 0:
                # near the mirror direction, where the lobe's anisotropy shows
                spread = 2.0 * max(alpha, alpha_t) * rng.uniform()
                phi = 2.0 * math.pi * rng.uniform()
                mirror = [-wi[0], -wi[1], wi[2]]
                wo = [mirror[0] + spread * math.cos(phi), mirror[1] + spread * math.sin(phi),
                      mirror[2]]
                length = math.sqrt(sum(c * c for c in wo))
                wo = [c / length for c in wo]
                if wo[2] <= 0.02:
                    wo = above(rng, 0.05)
            else:
                wo = above(rng, 0.05)
            si = dr.zeros(mi.SurfaceInteraction3f)
            si.wi = mi.Vector3f(*wi)
            si.sh_frame = mi.Frame3f(mi.Vector3f(0.0, 0.0, 1.0))
            value = bsdf.eval(mi.BSDFContext(), si, mi.Vector3f(*wo))
            rows.append({"alpha": alpha, "alpha_t": alpha_t, "rotation": rotation,
                         "wi": wi, "wo": wo, "f_cos": float(value.x[0])})
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out, "w", encoding="utf-8", newline="\n") as f:
        json.dump({"generator": "tools/mitsuba/brdf_table.py", "mitsuba": mi.__version__,
                   "rows": rows}, f, indent=1)
        f.write("\n")
    print("wrote %d rows to %s" % (len(rows), out))


if __name__ == "__main__":
    main()
