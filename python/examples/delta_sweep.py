"""Error against time over δ for each culling strategy, the speed-versus-accuracy trade of the
paper, scripted with the slc Python package and plotted with matplotlib.

    python python/examples/delta_sweep.py --out delta_sweep.png

The scene is loaded once; every (strategy, δ) renders the same VPLs and ξ (same seed). The
error is the RMSE of the indirect image against every VPL with p = 1 (reference="vpl"), the
time the median culling + shading time over --repeat renders.
"""

import argparse
import statistics

import matplotlib

matplotlib.use("Agg")  # headless: write a file, open no window
import matplotlib.pyplot as plt
import numpy as np

import slc


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene", nargs="?", default=None, help="file or built-in name")
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--rsm", type=int, default=32)
    parser.add_argument("--delta", type=float, nargs="+", default=[1e-4, 1e-3, 1e-2, 1e-1])
    parser.add_argument("--culling", nargs="+", default=["ellipsoid", "sphere", "clustered"])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", default="delta_sweep.png")
    args = parser.parse_args()

    scene = slc.Scene(args.scene)
    frame = dict(width=args.width, height=args.height, rsm=args.rsm)
    reference = scene.render(reference="vpl", **frame).indirect

    plt.figure(figsize=(6, 4))
    for strategy in args.culling:
        times, errors = [], []
        for delta in args.delta:
            runs = [
                scene.render(culling=strategy, delta=delta, **frame)
                for _ in range(args.repeat)
            ]
            ms = [r.report["timings_ms"]["culling"] + r.report["timings_ms"]["shading"] for r in runs]
            rmse = float(np.sqrt(np.mean((runs[-1].indirect - reference) ** 2)))
            times.append(statistics.median(ms))
            errors.append(rmse)
            print(f"{strategy:>10} δ={delta:<8g} {times[-1]:8.2f} ms  RMSE {rmse:.4e}")
        plt.loglog(times, errors, "o-", label=strategy)
    plt.xlabel("culling + shading (ms, median)")
    plt.ylabel("RMSE of indirect vs all VPLs")
    plt.title(f"{scene.name}: δ in {args.delta}")
    plt.legend()
    plt.tight_layout()
    plt.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
