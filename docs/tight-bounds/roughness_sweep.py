#!/usr/bin/env python3
"""The paper's Fig. 10 for the tight strategies: false positives per culling strategy over the
roughness of Sponza's floor (scenes/sponza.toml, glossy VPLs only, 640x360, RSM 128).

Runs `slc compare` once per alpha with the floor's alpha overridden and writes, next to this
script, roughness.csv / roughness.json (one row per alpha and strategy) and roughness.svg.

    python3 docs/tight-bounds/roughness_sweep.py [path/to/slc]
"""
import csv
import json
import pathlib
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
SLC = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/slc")
ALPHAS = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0]
STRATEGIES = ["sphere", "ellipsoid", "clustered", "tight", "clustered-tight"]


def scene_with_floor_alpha(alpha, folder):
    """scenes/sponza.toml with the floor's alpha replaced, its OBJ path made absolute."""
    text = (ROOT / "scenes/sponza.toml").read_text()
    obj = (ROOT / "scenes" / "../../shared/scenes/sponza/sponza.obj").resolve()
    text = text.replace('scene = "../../shared/scenes/sponza/sponza.obj"', f'scene = "{obj}"')
    assert "alpha = 0.1" in text
    text = text.replace("alpha = 0.1", f"alpha = {alpha}")
    path = pathlib.Path(folder) / f"sponza-alpha-{alpha}.toml"
    path.write_text(text)
    return path


def main():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for alpha in ALPHAS:
            scene = scene_with_floor_alpha(alpha, tmp)
            out = pathlib.Path(tmp) / f"out-{alpha}"
            subprocess.run(
                [SLC, "compare", str(scene), "--lobes", "glossy", "--rsm", "128",
                 "--width", "640", "--height", "360", "--no-reference",
                 "--culling", ",".join(STRATEGIES), "--out", str(out)],
                check=True, stdout=subprocess.DEVNULL)
            for s in STRATEGIES:
                r = json.loads((out / s / "report.json").read_text())
                m, t = r["metrics"], r["timings_ms"]
                rows.append({
                    "alpha": alpha, "strategy": s,
                    "false_positive_pairs": m["false_positive_pairs"],
                    "true_positive_pairs": m["true_positive_pairs"],
                    "missed_pairs": m["missed_pairs"],
                    "lights_per_pixel": round(m["lights_per_pixel_mean"], 3),
                    "culling_ms": round(t["culling"], 2),
                    "shading_ms": round(t["shading"], 2),
                })
            print(f"alpha {alpha}: " + ", ".join(
                f"{r['strategy']} {r['false_positive_pairs']}" for r in rows[-len(STRATEGIES):]))
    with open(HERE / "roughness.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (HERE / "roughness.json").write_text(json.dumps(rows, indent=1) + "\n")
    plot(rows)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for s in STRATEGIES:
        pts = [(r["alpha"], r["false_positive_pairs"]) for r in rows if r["strategy"] == s]
        ax.plot([a for a, _ in pts], [fp for _, fp in pts], marker="o", label=s)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("GGX α of the floor")
    ax.set_ylabel("false-positive pixel-VPL pairs")
    ax.set_title("Sponza, glossy VPLs, 640×360, RSM 128, δ = 1e-3, K = 8")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(HERE / "roughness.svg", metadata={"Date": None})


if __name__ == "__main__":
    main()
