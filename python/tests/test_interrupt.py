"""Ctrl-C stops every call that can take long: KeyboardInterrupt within a fraction of a second (2 s
allowed for a loaded machine), the process stays usable, nothing half-written is left behind."""
import json
import subprocess
import sys
import textwrap

import pytest

from conftest import SOURCE_DIR, SPHERE_SCENE, TINY_SCENE, child_env

# Runs SETUP, then CALL in the main thread while a timer thread sends SIGINT after DELAY seconds;
# prints what happened as JSON (CHECK: an expression evaluated afterwards, e.g. how much of `out` the
# call filled).
HARNESS = """
import json, signal, threading, time
import numpy as np
import penumbra
{setup}
main = threading.main_thread().ident
sent = []
def interrupt():
    sent.append(time.monotonic())
    signal.pthread_kill(main, signal.SIGINT)
timer = threading.Timer({delay}, interrupt)
started = time.monotonic()
timer.start()
try:
    {call}
    outcome = "returned"
except KeyboardInterrupt:
    outcome = "interrupted"
ended = time.monotonic()
timer.cancel()
check = {check}
# The module is still usable afterwards.
usable = penumbra.scene_from_string({tiny!r}).render(spp=1).spp == 1
print(json.dumps({{"outcome": outcome, "latency": ended - sent[0] if sent else None,
                  "seconds": ended - started, "check": check, "usable": usable}}))
"""


def interrupted(setup, call, delay, check="None", cwd=None, timeout=120):
    code = HARNESS.format(setup=textwrap.dedent(setup), call=call, delay=delay, check=check, tiny=TINY_SCENE)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout,
                          cwd=cwd, env=child_env(PENUMBRA_SOURCE_DIR=str(SOURCE_DIR)))
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


SPHERE = f"scene = penumbra.load_scene({str(SPHERE_SCENE)!r}, overrides={{'camera.width': 96, 'camera.height': 64}})"
LONG_CALLS = {
    "render_spp": (SPHERE, "scene.render(spp=1 << 30)"),
    "render_time": (SPHERE, "scene.render(time=1e9)"),
    "converge_time": (SPHERE + "\nref = scene.render(spp=4).mean",
                      "penumbra.converge(scene, strategies='area', time=30, reference=ref)"),
    "converge_spp": (SPHERE + "\nref = scene.render(spp=4).mean",
                     "penumbra.converge(scene, strategies='area', spp=1 << 24, reference=ref)"),
    "chi2_samples": ("", "penumbra.chi2_test('beckmann', samples=10**9)"),
    "chi2_quadrature": ("", "penumbra.chi2_test('cosine-hemisphere', samples=10**7, res=1000)"),
    "sample_points": ("", "penumbra.sample_points('independent', 1 << 22, dims=(8190, 8191))"),
    # A sharp lobe whose quadrature takes tens of seconds inside its one block of cells.
    "bsdf_chi2_quadrature": ("", "penumbra.bsdf_chi2_test('roughconductor', samples=2000, res=2, alpha=0.001, "
                                 "distribution='ggx', incident=80)"),
}


@pytest.mark.parametrize("name", sorted(LONG_CALLS))
def test_keyboard_interrupt_stops_long_calls(name):
    setup, call = LONG_CALLS[name]
    r = interrupted(setup, call, delay=1.0)
    assert r["outcome"] == "interrupted", r
    assert r["latency"] < 2.0, f"{name}: KeyboardInterrupt {r['latency']:.2f} s after SIGINT"
    assert r["usable"]


def test_keyboard_interrupt_while_converge_renders_its_reference(tmp_path):
    # No reference given and none cached: converge renders one (4096 spp), which Ctrl-C stops, and
    # the cache (next to the scene: here the working directory) is not written.
    setup = (f"scene = penumbra.scene_from_string(open({str(SPHERE_SCENE)!r}).read(), "
             f"base_dir={str(SPHERE_SCENE.parent)!r}, overrides={{'camera.width': 96, 'camera.height': 64, "
             f"'integrator.nSamples': 16}})")
    r = interrupted(setup, "penumbra.converge(scene, strategies='area', spp=4)", delay=1.0, cwd=tmp_path)
    assert r["outcome"] == "interrupted" and r["latency"] < 2.0, r
    assert list(tmp_path.iterdir()) == []


# The array functions work in chunks: interrupted, they stop early and `out` keeps the points done.
CHUNKED = {
    "warp": ("u = penumbra.random_points(1 << 23, seed=2)\nout = np.full((1 << 23, 3), np.nan, np.float32)",
             "penumbra.warp('beckmann', u, out=out)"),
    "pdf": ("v = penumbra.warp('beckmann', penumbra.random_points(1 << 23, seed=2))\n"
            "out = np.full(1 << 23, np.nan, np.float32)",
            "penumbra.pdf('beckmann', v, out=out)"),
    "random_points": ("out = np.full((1 << 24, 2), np.nan, np.float32)",
                      "penumbra.random_points(1 << 24, seed=3, out=out)"),
}


@pytest.mark.parametrize("name", sorted(CHUNKED))
def test_keyboard_interrupt_stops_array_functions_early(name):
    setup, call = CHUNKED[name]
    r = interrupted(setup, call, delay=0.01, check="float(np.mean(~np.isnan(out.reshape(len(out), -1)[:, 0])))")
    assert r["outcome"] == "interrupted", r
    assert r["check"] < 1.0, f"{name} ran to the end ({r['seconds']:.2f} s) before KeyboardInterrupt"
    assert r["latency"] < 2.0 and r["usable"]
