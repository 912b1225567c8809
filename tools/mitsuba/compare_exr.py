#!/usr/bin/env python3
"""Compares two reference renders (e.g. a fresh low-resolution render of cornell-a against the
stored one) image by image, using both sides' per-pixel standard errors.

The stored image may have an integer multiple of the test image's resolution: it is then
box-downsampled (exact for a box pixel filter: a big pixel's value is the mean of its
sub-pixels; standard errors combined as sqrt(sum se^2) / k^2).

For each of direct / indirect / total: the image means of both sides, their difference in units
of its standard error, and the per-pixel z = (a - b) / sqrt(se_a^2 + se_b^2): mean, RMS (1 for
agreement within noise), fraction of |z| > 3 / > 4 (0.27 % / 0.006 % for Gaussian noise), and
the median relative per-pixel difference.

Usage:
    python tools/mitsuba/compare_exr.py TEST_DIR STORED_DIR
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import render_reference  # noqa: E402,F401  (selects the variant / libLLVM)
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402


def read_exr(path):
    bmp = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, False)
    w, h = bmp.size()
    t = mi.TensorXf(bmp)
    return w, h, [float(v) for v in dr.ravel(t.array)]


def downsample(w, h, vals, k, is_se):
    W, H = w // k, h // k
    out = []
    for J in range(H):
        for I in range(W):
            for c in range(3):
                acc = 0.0
                for j in range(J * k, J * k + k):
                    for i in range(I * k, I * k + k):
                        v = vals[3 * (j * w + i) + c]
                        acc += v * v if is_se else v
                out.append(math.sqrt(acc) / (k * k) if is_se else acc / (k * k))
    return W, H, out


def main():
    test_dir, ref_dir = sys.argv[1], sys.argv[2]
    report = {}
    for key in ("direct", "indirect", "total"):
        wa, ha, a = read_exr(os.path.join(test_dir, key + ".exr"))
        _, _, sa = read_exr(os.path.join(test_dir, key + "_stderr.exr"))
        wb, hb, b = read_exr(os.path.join(ref_dir, key + ".exr"))
        _, _, sb = read_exr(os.path.join(ref_dir, key + "_stderr.exr"))
        if (wb, hb) != (wa, ha):
            k = wb // wa
            assert wb == k * wa and hb == k * ha, "resolutions are not integer multiples"
            _, _, b = downsample(wb, hb, b, k, False)
            _, _, sb = downsample(wb, hb, sb, k, True)
        n = wa * ha
        mean_a = [sum(a[c::3]) / n for c in range(3)]
        mean_b = [sum(b[c::3]) / n for c in range(3)]
        se_mean = [math.sqrt(sum(x * x for x in sa[c::3]) + sum(x * x for x in sb[c::3])) / n
                   for c in range(3)]
        zs, rel = [], []
        for x, y, s1, s2 in zip(a, b, sa, sb):
            s = math.sqrt(s1 * s1 + s2 * s2)
            if s > 0:
                zs.append((x - y) / s)
            elif x != y:
                zs.append(float("inf"))
            if y > 1e-3:
                rel.append(abs(x - y) / y)
        rel.sort()
        za = [abs(z) for z in zs]
        r = {
            "mean_test": [round(v, 6) for v in mean_a],
            "mean_stored": [round(v, 6) for v in mean_b],
            "mean_diff_in_se": [round((x - y) / s, 2) for x, y, s in zip(mean_a, mean_b, se_mean)],
            "px_z_mean": round(sum(zs) / len(zs), 4),
            "px_z_rms": round(math.sqrt(sum(z * z for z in zs) / len(zs)), 4),
            "px_frac_abs_z_gt3": round(sum(1 for z in za if z > 3) / len(za), 5),
            "px_frac_abs_z_gt4": round(sum(1 for z in za if z > 4) / len(za), 5),
            "px_max_abs_z": round(max(za), 2),
            "px_rel_diff_median": round(rel[len(rel) // 2], 5),
            "values_compared": len(zs),
        }
        report[key] = r
        print(key, json.dumps(r))
    return report


if __name__ == "__main__":
    main()
