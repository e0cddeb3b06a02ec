#!/usr/bin/env python3
"""Render the sphere scene with two light-sampling strategies at equal time; plot RMSE against time.

  PYTHONPATH=build/python python3 python/examples/compare_strategies.py -o compare.png
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import penumbra  # noqa: E402

SCENE = pathlib.Path(__file__).resolve().parents[2] / "scenes" / "hw2" / "Tests" / "sphere-solid.xml"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", default="compare_strategies.png")
    ap.add_argument("--strategies", default="area,solid-angle")
    ap.add_argument("--time", type=float, default=3.0, help="seconds per strategy")
    ap.add_argument("--quick", action="store_true", help="small image, short runs (the test suite)")
    args = ap.parse_args()

    size = (96, 64) if args.quick else (256, 256)
    seconds = 0.5 if args.quick else args.time
    scene = penumbra.load_scene(str(SCENE), overrides={"camera.width": size[0], "camera.height": size[1]})
    # Reference: the lowest-variance strategy, many samples, a seed no run uses; passing the whole
    # result lets the error measurement subtract the reference's own noise.
    scene.set("integrator.measure", "solid-angle")
    reference = scene.render(spp=256 if args.quick else 1024, seed=12345, progress=not args.quick)
    runs = penumbra.converge(scene, strategies=args.strategies, time=seconds, reference=reference, seed=1)

    fig = plt.figure(figsize=(12, 4.2), constrained_layout=True)
    grid = fig.add_gridspec(1, 2 + len(runs), width_ratios=[2, 0.05] + [1] * len(runs))
    ax = fig.add_subplot(grid[0, 0])
    for name, m in runs.items():
        # Pixels that see the light directly are left out: their filter-edge noise is the same for
        # every light-sampling strategy and would hide the difference.
        ax.loglog(m["seconds"], m["rmse_nolight"], "o-", ms=3, label=f"{m['label']} ({m['spp'][-1]} spp)")
        # Reference line of slope -1/2 through the last point: unbiased Monte Carlo.
        t = m["seconds"]
        ax.loglog(t, m["rmse_nolight"][-1] * np.sqrt(t[-1] / t), ":", color=ax.lines[-1].get_color(), lw=1)
    ax.set_xlabel("rendering time [s]")
    ax.set_ylabel("RMSE (pixels that do not see the light)")
    ax.set_title(f"{SCENE.name}, {size[0]}x{size[1]}, equal time {seconds:g} s")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    for i, (name, m) in enumerate(runs.items()):
        img = fig.add_subplot(grid[0, 2 + i])
        img.imshow(np.clip(m["final_image"], 0, 1) ** (1 / 2.2))
        img.set_title(f"{m['label']}\nRMSE {m['rmse_nolight'][-1]:.3g}")
        img.axis("off")
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
