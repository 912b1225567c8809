"""False positives per culling strategy against the GGX roughness of one material, in the
spirit of the paper's Fig. 10: the rougher the lobe, the larger every bound, and the more the
ellipsoid gains over the sphere as the lobe narrows.

    python python/examples/roughness_sweep.py --out roughness_sweep.png
    python python/examples/roughness_sweep.py scenes/sponza.toml --material "sp_00_pod" --lobes glossy

For each alpha the scene is copied with the material overridden (``Scene.with_materials``),
and every strategy is compared on the same VPLs and ξ with culling metrics. Writes the plot
and the same numbers as CSV (``--out`` with ``.csv``).
"""

import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless: write a file, open no window
import matplotlib.pyplot as plt

import slc


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=None, help="file or built-in name")
    parser.add_argument("--material", default="copper", help="material name or glob")
    parser.add_argument("--alpha", type=float, nargs="+", default=[0.01, 0.03, 0.1, 0.3, 1.0])
    parser.add_argument("--culling", nargs="+", default=["sphere", "ellipsoid", "clustered"])
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--rsm", type=int, default=32)
    parser.add_argument("--lobes", default="both")
    parser.add_argument("--out", default="roughness_sweep.png")
    args = parser.parse_args()

    base = slc.Scene(args.scene)
    frame = dict(width=args.width, height=args.height, rsm=args.rsm, lobes=args.lobes)
    rows = []
    for alpha in args.alpha:
        scene = base.with_materials(args.material, alpha=alpha)
        frames = scene.compare(culling=args.culling, reference=False, **frame)
        for strategy, f in frames.items():
            m = f.report["metrics"]
            rows.append(
                dict(
                    alpha=alpha,
                    strategy=strategy,
                    lights_per_pixel=m["lights_per_pixel_mean"],
                    false_positives_per_pixel=m["false_positive_pairs"] / (args.width * args.height),
                    false_discovery_rate=m["false_discovery_rate"],
                    missed=m["missed_pairs"],
                )
            )
            print(f"alpha {alpha:<6g} {strategy:>10}: {rows[-1]['false_positives_per_pixel']:8.2f} FP/pixel, "
                  f"FDR {m['false_discovery_rate']:.3f}, missed {m['missed_pairs']}")

    table = Path(args.out).with_suffix(".csv")
    with open(table, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    plt.figure(figsize=(6, 4))
    for strategy in args.culling:
        points = [r for r in rows if r["strategy"] == strategy]
        plt.semilogx([r["alpha"] for r in points],
                     [r["false_positives_per_pixel"] for r in points], "o-", label=strategy)
    plt.xlabel(f"GGX alpha of '{args.material}'")
    plt.ylabel("false positives per pixel")
    plt.title(f"{base.name}: culling against roughness")
    plt.legend()
    plt.tight_layout()
    plt.savefig(args.out, dpi=120)
    print(f"wrote {args.out} and {table}")


if __name__ == "__main__":
    main()
