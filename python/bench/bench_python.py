#!/usr/bin/env python3
"""Python module against the C++ it wraps, in the same run (not a test: timings on a shared machine).

  PYTHONPATH=build/python /usr/bin/python3 python/bench/bench_python.py [--runs 5]

1. Rendering: the assignment's sphere scene at 16 spp, `penumbra render` and Scene.render()
   alternating; the engine's own seconds (what both print) and the wall time of the whole job
   (CLI: process start to exit; Python: load, render, save), medians.
2. Warps: penumbra.warp on 10^7 float32 points against the micro-benchmark BM_Warp (ns per sample,
   build/penumbra_bench), in CPU time (wall time on a shared machine mostly measures the neighbours),
   into a reused out= array and into a new array (whose first touch of 80-120 MB of fresh pages,
   kernel time, the micro-benchmark does not pay).
"""
import argparse
import json
import resource
import pathlib
import re
import statistics
import subprocess
import tempfile
import time

import penumbra

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "hw2" / "Tests" / "sphere-solid.xml"
WARPS = {"cosine-hemisphere": ("cosine_hemisphere", None), "uniform-disk": ("uniform_disk", None),
         "beckmann": ("beckmann", 0.2), "uniform-cone": ("uniform_cone", 0.9)}


def bench_render(runs, build):
    cli_engine, cli_wall, py_engine, py_wall, cli_cpu, py_cpu = [], [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(runs):
            c = resource.getrusage(resource.RUSAGE_CHILDREN)
            t = time.perf_counter()
            out = subprocess.run([str(build / "penumbra"), "render", str(SCENE), "--spp", "16", "-o",
                                  f"{tmp}/cli.exr"], capture_output=True, text=True, check=True).stdout
            cli_wall.append(time.perf_counter() - t)
            c2 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cli_cpu.append(c2.ru_utime + c2.ru_stime - c.ru_utime - c.ru_stime)
            cli_engine.append(float(re.search(r"spp, ([0-9.]+) s", out).group(1)))
            c = time.process_time()
            t = time.perf_counter()
            r = penumbra.load_scene(str(SCENE)).render(spp=16)
            r.save(f"{tmp}/py.exr")
            py_wall.append(time.perf_counter() - t)
            py_cpu.append(time.process_time() - c)
            py_engine.append(r.seconds)
    for name, c, p in (("engine seconds", cli_engine, py_engine), ("whole job wall", cli_wall, py_wall),
                       ("whole job CPU", cli_cpu, py_cpu)):
        mc, mp = statistics.median(c), statistics.median(p)
        pairs = statistics.median(b / a for a, b in zip(c, p))
        print(f"render 16 spp, {name:15s}: CLI {mc:.3f} s  Python {mp:.3f} s  Python/CLI {mp / mc:.3f} "
              f"(median of pairs {pairs:.3f})"
              f"   (CLI {' '.join(f'{x:.3f}' for x in c)}; Python {' '.join(f'{x:.3f}' for x in p)})")


def bench_warps(build):
    out = subprocess.run([str(build / "penumbra_bench"), "--benchmark_format=json",
                          "--benchmark_filter=^BM_Warp/(" + "|".join(v[0] for v in WARPS.values()) + ")$"],
                         capture_output=True, text=True, check=True).stdout
    cpp = {b["name"].split("/")[1]: b["cpu_time"] for b in json.loads(out)["benchmarks"]}  # ns per sample
    n = 10_000_000
    u = penumbra.random_points(n, seed=1)
    for name, (bench_name, param) in WARPS.items():
        out = penumbra.warp(name, u, param=param)  # faults the output's pages in once
        fresh = min(_cpu(lambda: penumbra.warp(name, u, param=param)) for _ in range(3)) / n * 1e9
        reused = min(_cpu(lambda: penumbra.warp(name, u, param=param, out=out)) for _ in range(3)) / n * 1e9
        c = cpp[bench_name]
        print(f"warp {name:18s} 1e7 points, ns/sample CPU: C++ BM_Warp {c:5.2f} | Python out= {reused:5.2f} "
              f"({c / reused:.2f}x the C++ rate) | Python new array {fresh:5.2f} ({c / fresh:.2f}x)")


def _cpu(f):
    t = time.process_time()
    f()
    return time.process_time() - t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--build", type=pathlib.Path, default=ROOT / "build")
    args = ap.parse_args()
    bench_render(args.runs, args.build)
    bench_warps(args.build)


if __name__ == "__main__":
    main()
