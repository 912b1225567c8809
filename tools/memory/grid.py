#!/usr/bin/env python3
"""Peak RSS of `slc render` against its memory estimate over a grid of sizes, scenes, shaders
and lobes (docs/memory.md shows the table this prints).

Each case runs `slc render ... --out DIR` once; report.json gives `memory.estimate_bytes` (what
the check before any work compares with the memory available) and `memory.peak_rss_bytes`
(VmHWM at the end of the run). Prints a Markdown table and exits 1 if any peak exceeds its
estimate.

Usage (from the repository root, after `cargo build --release -p slc-app`):
    python3 tools/memory/grid.py [--slc target/release/slc] [--quick] [--provenance FILE]

`--provenance FILE` writes the first run's provenance (slc's commit, CPU, date) as JSON to FILE
(tools/regen-docs puts it above the table in docs/memory.md).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

SPONZA = "scenes/sponza.toml"

# (scene, width, height, rsm, extra arguments)
FULL = [
    (None, 256, 256, 64, ""),
    (None, 512, 512, 64, ""),
    (None, 1024, 1024, 64, ""),
    (None, 2048, 2048, 64, ""),
    (None, 512, 512, 16, ""),
    (None, 512, 512, 256, ""),
    (None, 512, 512, 256, "--lobes diffuse"),
    (None, 512, 512, 256, "--lobes glossy"),
    (None, 512, 512, 256, "--culling none"),
    (None, 512, 512, 256, "--culling clustered"),
    (None, 512, 512, 128, "--metrics"),
    (None, 512, 512, 128, "--shader vsgl --vsgls 4096"),
    (None, 1024, 1024, 64, "--shader vsgl --vsgls 4096"),
    (None, 128, 128, 32, "--reference vpl"),
    (None, 128, 128, 16, "--reference path --spp 4"),
    (None, 4096, 4096, 16, ""),
    (SPONZA, 640, 360, 64, ""),
    (SPONZA, 1920, 1080, 128, ""),
    (SPONZA, 1920, 1080, 256, "--lobes glossy --culling ellipsoid"),
    (SPONZA, 640, 360, 128, "--shader vsgl --vsgls 1024"),
]
QUICK = [c for c in FULL if c[1] * c[2] <= 1024 * 1024 and c[0] is None][:6]


def run(slc, case, out):
    scene, w, h, rsm, extra = case
    cmd = [slc, "render"] + ([scene] if scene else []) + [
        "--width", str(w), "--height", str(h), "--rsm", str(rsm), "--out", out] + extra.split()
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)}: {done.stderr}")
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    return report["memory"], report["vpl_count"], report["provenance"]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--slc", default="target/release/slc")
    p.add_argument("--quick", action="store_true", help="the small cases only")
    p.add_argument("--provenance", help="write the first run's provenance (JSON) here")
    args = p.parse_args()
    mib = 1 << 20
    print("| scene | size | RSM | options | VPLs | estimate MiB | peak RSS MiB | peak / estimate |")
    print("|---|---|---|---|---|---|---|---|", flush=True)
    over = 0
    with tempfile.TemporaryDirectory() as tmp:
        for i, case in enumerate(QUICK if args.quick else FULL):
            memory, vpls, provenance = run(args.slc, case, os.path.join(tmp, str(i)))
            if i == 0 and args.provenance:
                with open(args.provenance, "w") as f:
                    json.dump(provenance, f)
            est, peak = memory["estimate_bytes"], memory["peak_rss_bytes"]
            over += peak > est
            scene, w, h, rsm, extra = case
            print(f"| {scene or 'default'} | {w}x{h} | {rsm} | {extra or '-'} | {vpls} | "
                  f"{est / mib:.0f} | {peak / mib:.0f} | {peak / est:.2f} |", flush=True)
    sys.exit(1 if over else 0)


if __name__ == "__main__":
    main()
