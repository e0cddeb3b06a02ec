#!/usr/bin/env python3
"""Draw a warp's samples and its chi-square histogram (observed against expected counts).

  PYTHONPATH=build/python python3 python/examples/warp_histogram.py --warp beckmann --param 0.3 -o warp.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import penumbra  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", default="warp_histogram.png")
    ap.add_argument("--warp", default="cosine-hemisphere", choices=penumbra.warp_names())
    ap.add_argument("--param", type=float, default=None)
    ap.add_argument("--points", type=int, default=4000, help="samples drawn in the scatter plot")
    ap.add_argument("--samples", type=int, default=1_000_000, help="samples of the chi-square test")
    ap.add_argument("--quick", action="store_true", help="fewer samples (the test suite)")
    args = ap.parse_args()
    samples = 100_000 if args.quick else args.samples

    pts = penumbra.warp(args.warp, penumbra.random_points(args.points, seed=7), param=args.param)
    test = penumbra.chi2_test(args.warp, samples=samples, res=25, param=args.param)

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.3), constrained_layout=True)
    ax = axes[0]
    if pts.shape[1] == 3:
        ax.scatter(pts[:, 0], pts[:, 1], c=pts[:, 2], s=2, cmap="viridis")
        ax.set_title(f"{args.warp}: {args.points} samples (x, y; colour z)")
    else:
        ax.scatter(pts[:, 0], pts[:, 1], s=2)
        ax.set_title(f"{args.warp}: {args.points} samples")
    ax.set_aspect("equal")
    spherical = pts.shape[1] == 3
    extent = [0, 2 * np.pi, 0, 1] if spherical else None
    vmax = max(test.observed.max(), test.expected.max())
    for ax, counts, title in ((axes[1], test.observed, "observed"), (axes[2], test.expected, "expected")):
        im = ax.imshow(counts, origin="lower", vmin=0, vmax=vmax, aspect="auto", extent=extent, cmap="magma")
        ax.set_title(f"{title} counts")
        if spherical:
            ax.set_xlabel("phi")
            ax.set_ylabel("1 - cos(theta) (scaled)")
    fig.colorbar(im, ax=axes[2])
    fig.suptitle(f"chi2 {test.chi2:.1f}, dof {test.dof}, p-value {test.p_value:.3g}: {test.verdict} "
                 f"({samples} samples)")
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
