#!/usr/bin/env python3
"""The paper's Fig. 11 case: a highly specular floor (GGX alpha 0.02) needs far more VPLs,
here Sponza's floor at alpha 0.02 with 1.04M glossy VPLs, beside alpha 0.1 at 65k.

For each case runs `slc compare` twice: at 480x270 for each strategy's culling and shading
(median of 3 runs), false positives and missed pairs, and at 160x90 with the all-VPL reference
(every VPL at every pixel with p = 1, the same VPLs) for the RMSE and mean FLIP of the image
(filtered, as the paper's pipeline makes it) against it; the RMSE also relative to the
reference's mean indirect radiance. Writes specular_floor.json next to this script.

    python3 docs/many-vpls/specular_floor.py [path/to/slc]
"""
import json
import pathlib
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
SLC = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/slc")
# Times at the 480x270; the error against the reference (every VPL at every pixel:
# 1.5e10 pairs at 1M VPLs, minutes on 2 cores) at 160x90.
TIMED, CHECKED = (480, 270), (160, 90)
STRATEGIES = "ellipsoid,binned"
# (floor alpha, RSM per face): 288² texels make 65k glossy VPLs, 1152² make 1.04M.
CASES = [(0.1, 288), (0.02, 288), (0.02, 1152)]

# Sponza with its floor's alpha replaced, as the roughness sweep makes it.
sys.path.insert(0, str(ROOT / "docs/tight-bounds"))
from roughness_sweep import scene_with_floor_alpha  # noqa: E402


def compare(scene, shown, rsm, size, extra, out):
    """Runs slc compare on `scene` (shown as `shown`); returns compare.json, the reference's
    report.json (or None), the seconds it took and the command as the table gives it."""
    args = ["--lobes", "glossy", "--rsm", str(rsm), "--width", str(size[0]),
            "--height", str(size[1]), "--culling", STRATEGIES, *extra]
    start = time.monotonic()
    subprocess.run([SLC, "compare", str(scene), *args, "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL, cwd=ROOT)
    seconds = time.monotonic() - start
    reference = out / "reference_vpl/report.json"
    return (json.loads((out / "compare.json").read_text()),
            json.loads(reference.read_text()) if reference.exists() else None,
            round(seconds, 1), " ".join(["slc compare", shown, *args]))


def main():
    rows, provenance = [], None
    with tempfile.TemporaryDirectory() as tmp:
        for alpha, rsm in CASES:
            scene = scene_with_floor_alpha(alpha, tmp)
            shown = f"<sponza.toml, floor alpha {alpha}>"
            timed, _, _, timed_command = compare(scene, shown, rsm, TIMED, [
                "--no-reference", "--repeat", "3"], pathlib.Path(tmp) / f"t-{alpha}-{rsm}")
            checked, reference, seconds, checked_command = compare(
                scene, shown, rsm, CHECKED, [], pathlib.Path(tmp) / f"r-{alpha}-{rsm}")
            provenance = provenance or timed["provenance"]
            mean = sum(reference["image_means"]["indirect"]) / 3
            for t, c in zip(timed["rows"], checked["rows"]):
                rows.append({
                    "alpha": alpha, "rsm": rsm, "vpls": timed["settings"]["vpls"],
                    "strategy": t["strategy"],
                    "culling_ms": round(t["culling_ms"], 2),
                    "shading_ms": round(t["shading_ms"], 2),
                    "culling_plus_shading_ms": round(t["culling_plus_shading_ms"], 2),
                    "true_positives": t["true_positives"],
                    "false_positives": t["false_positives"],
                    "missed": t["missed"],
                    "rmse_vs_reference": c["rmse_vs_reference"],
                    "relative_rmse": c["rmse_vs_reference"] / mean,
                    "flip_vs_reference": c["flip_vs_reference"],
                    "missed_at_reference_size": c["missed"],
                    "reference_mean_indirect": mean,
                    "reference_command_seconds": seconds,
                    "timed_command": timed_command,
                    "reference_command": checked_command,
                })
            print(f"alpha {alpha}, RSM {rsm}: {rows[-1]['vpls']} VPLs, "
                  + ", ".join(f"{r['strategy']} {r['culling_plus_shading_ms']:.1f} ms"
                              for r in rows[-2:])
                  + f", relative RMSE {rows[-1]['relative_rmse']:.3f} ({seconds:.0f} s)")
    data = {"provenance": provenance, "timed": TIMED, "checked": CHECKED, "rows": rows}
    (HERE / "specular_floor.json").write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    main()
