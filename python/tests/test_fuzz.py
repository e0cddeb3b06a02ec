"""A seeded random-argument campaign over every public function of the module: each call mixes valid
arguments with hostile ones (NaN, infinities, boundary and huge integers, wrong types, NUL characters,
odd arrays, overlapping outputs) and must return a well-formed result or raise ValueError, TypeError,
MemoryError or OSError; never crash, hang or leak another exception. A call still running after
CALL_SECONDS is interrupted by SIGALRM (a handler that raises, as Ctrl-C's does) and must stop within
a second. The sanitizer job runs it under AddressSanitizer and UBSan (tools/sanitize asan).

Bounded by PENUMBRA_FUZZ_CALLS (default 300) and PENUMBRA_FUZZ_SECONDS (default 20); seeded by
PENUMBRA_FUZZ_SEED (default 1), which a failure report names."""
import faulthandler
import math
import os
import pathlib
import random
import signal
import time
import warnings

import numpy as np

import penumbra
from conftest import SPHERE_SCENE, TINY_SCENE

CALL_SECONDS = 2.0  # then SIGALRM interrupts the call
STOP_SECONDS = 1.5  # allowed from SIGALRM to the call's end
NAN, INF = math.nan, math.inf
ALLOWED = (ValueError, TypeError, MemoryError, OSError)


class CallTimeout(Exception):
    """Raised by the SIGALRM handler inside a call that ran longer than CALL_SECONDS."""


class Fresh:
    """A value made anew for each call (arrays the call may write, scenes it may change)."""

    def __init__(self, make):
        self.make = make


class Arg:
    def __init__(self, good, bad=(), optional=True, receiver=False):
        # receiver: the object a method is called on (never hostile: Python's AttributeError is not ours)
        self.good, self.bad, self.optional, self.receiver = list(good), list(bad), optional, receiver


# Values every argument may get: the wrong type or no value at all.
CONFUSION = [None, "", "\x00", "x" * 5000, b"\xff\xfe", [], {}, (), object(), 1j, NAN, -1, 2**64, True,
             np.zeros(3), "\udcff"]
INT_EDGES = [0, -1, 2**31 - 1, 2**31, -2**31, 2**32, 2**63 - 1, -2**63, 2**63, 2**64, 10**30, 1.5, "1"]
FLOAT_EDGES = [NAN, INF, -INF, 0.0, -0.0, -1.0, 5e-324, 1e-300, 1e300, 10**400, "0.5"]
WARPS = penumbra.warp_names()
BSDFS = penumbra.bsdf_names()
# The BSDFs' parameters: valid values and the edges (alpha <= 0, NaN, incident past 89.99, kd outside
# [0, 1], IORs <= 0, unknown distributions).
BSDF_ARGS = {
    "alpha": Arg([0.1, 1e-3, 0.5, 1000.0], FLOAT_EDGES + [1e-6, 1001.0]),
    "incident": Arg([0.0, 30.0, 89.99], FLOAT_EDGES + [90.0, 95.0]),
    "kd": Arg([0.0, 0.5, 1.0], FLOAT_EDGES + [1.5]),
    "distribution": Arg(["beckmann", "ggx"], ["", "phong", "ggx\x00", 3]),
    "int_ior": Arg([1.5, 1.0], FLOAT_EDGES),
    "ext_ior": Arg([1.0, 1.000277], FLOAT_EDGES),
}
SAMPLERS = [s["name"] for s in penumbra.samplers()]
SMALL_SET_VALUES = [1, 2, 8, 16, 0.5, 30.0, "area", "solid-angle", "ao", "independent", "stratified", True]


def scene_factory():
    return penumbra.scene_from_string(TINY_SCENE, overrides={"camera.width": 8, "camera.height": 6})


def points(rng_seed, n, cols):
    g = np.random.default_rng(rng_seed)
    return g.random((n, cols), dtype=np.float32)


# Arrays of the warp's inputs: the right shape, and shapes, dtypes and contents that are not.
POINT_ARRAYS = [
    Fresh(lambda: points(1, 16, 2)), Fresh(lambda: points(2, 1, 2).astype(np.float64)),
    Fresh(lambda: np.zeros((0, 2), np.float32)), Fresh(lambda: points(3, 8, 3)),
    Fresh(lambda: (points(4, 8, 2) * 4 - 2)), Fresh(lambda: np.full((4, 2), NAN, np.float32)),
    Fresh(lambda: np.full((4, 3), INF)), Fresh(lambda: points(5, 8, 4)[:, ::2]),  # strided
    Fresh(lambda: points(6, 8, 2).astype(">f4")), Fresh(lambda: (points(7, 8, 2) * 10).astype(np.int64)),
    Fresh(lambda: np.broadcast_to(np.float32([0.3, 0.7]), (32, 2))), Fresh(lambda: np.zeros(6, np.float32)),
    Fresh(lambda: np.zeros((2, 2, 2), np.float32)), Fresh(lambda: np.full((2, 2), "a", dtype=object)),
    Fresh(lambda: [[0.1, 0.2], [0.3, 0.4]]), Fresh(lambda: points(8, 4, 1)), Fresh(lambda: np.zeros((3, 2), bool)),
]
OUT_ARRAYS = [None, None, Fresh(lambda: np.empty((16, 3), np.float32)), Fresh(lambda: np.empty((16, 2), np.float32)),
              Fresh(lambda: np.empty(16, np.float32)), Fresh(lambda: np.empty((16, 2))),
              Fresh(lambda: np.empty((16, 4), np.float32)[:, ::2]), "out", Fresh(lambda: np.empty((0, 2), np.float32))]
IMAGES = [None, Fresh(lambda: np.zeros((6, 8, 3), np.float32)), Fresh(lambda: np.full((2, 2, 3), NAN)),
          Fresh(lambda: np.zeros((0, 0, 3))), Fresh(lambda: np.zeros((2, 2))), Fresh(lambda: np.zeros((2, 2, 4))),
          Fresh(lambda: np.zeros((2, 2, 3), complex)), Fresh(lambda: np.full((2, 2, 3), "a", dtype=object)), "image"]


def specs(tmp: pathlib.Path):
    """name -> (callable taking keyword arguments, {argument: Arg})."""
    tiny_ref = Fresh(lambda: np.zeros((6, 8, 3), np.float32))
    paths = [str(tmp / "out.exr"), str(tmp / "out.pfm"), tmp / "out.png", os.fsencode(tmp / "bytes.pfm")]
    bad_paths = ["", "\x00", str(tmp / "no-dir" / "x.exr"), str(tmp / "x.bmp"), str(tmp), 3, "/proc/version",
                 str(tmp / "a\x00b.exr")]
    scene = Arg([Fresh(scene_factory)], optional=False, receiver=True)
    return {
        "load_scene": (penumbra.load_scene, {
            "path": Arg([str(SPHERE_SCENE), SPHERE_SCENE, os.fsencode(SPHERE_SCENE)],
                        ["", "\x00", "/nonexistent.xml", str(tmp), "/dev/null", 3, None, b"\xff.xml"], False),
            "overrides": Arg([None, {"camera.width": 8, "camera.height": 6}, {"sampler.sampleCount": 2}],
                             [[], "x", {"x": 1}, {"camera.width": NAN}, {"camera.width": 10**30}, {1: 2},
                              {"a\x00.b": 1}, {"camera.width": object()}, {"camera.width": 2**31}])}),
        "scene_from_string": (penumbra.scene_from_string, {
            "xml": Arg([TINY_SCENE], ["", "<scene>", "<scene/>", "\x00", TINY_SCENE.replace("<camera", "\x00<camera"),
                                      TINY_SCENE.encode("latin-1") + b"\xe9", "<scene>" + "<shape>" * 5000,
                                      TINY_SCENE.replace('value="2"', 'value="-2"'),
                                      TINY_SCENE.replace('"16"', '"99999999999"')], False),
            "base_dir": Arg(["", str(SPHERE_SCENE.parent)], ["\x00", 3, "/nonexistent"]),
            "name": Arg(["<string>", "fuzz.xml", "sc\u00e8ne.xml"], ["", "\x00", 3]),
            "overrides": Arg([None, {"camera.width": 4}], [{"camera.width": INF}, {"": 1}, {"sampler.": 2}])}),
        "Scene.set": (lambda scene, **kw: scene.set(**kw), {
            "scene": scene,
            "key": Arg(["camera.width", "camera.height", "sampler.sampleCount", "integrator.measure", "camera.fov",
                        "integrator.type", "sampler.type"],
                       ["", ".", "a.", ".b", "nope.x", "camera.\x00", "camera.width.x", "shape.radius"], False),
            "value": Arg(SMALL_SET_VALUES, [NAN, INF, -1, 0, 10**30, "", "\x00", None, [], "x" * 1000, 2**31],
                         False)}),
        "Scene.properties": (lambda scene: (scene.settings, scene.strategy, scene.axes, scene.sampler, scene.sample_count,
                                            scene.seed, scene.width, scene.height, scene.path, scene.warnings,
                                            scene.to_xml(), repr(scene)), {"scene": scene}),
        "Scene.render": (lambda scene, **kw: scene.render(**kw), {
            "scene": scene,
            "spp": Arg([None, 1, 2, 3], [0, -1, 2**30 + 1, 2**30] + INT_EDGES),
            "time": Arg([None, 0.01, 0.03], FLOAT_EDGES),
            "seed": Arg([0, 1, 2**63 - 1, 2**64 - 1], INT_EDGES),
            "threads": Arg([None, 1, 2], [0, -1, 1025, 2**40, 1.5]),
            "progress": Arg([None, False, lambda spp, s: None],
                            [3, "x", lambda: None, lambda spp, s: (_ for _ in ()).throw(ValueError("stop"))])}),
        "RenderResult.save": (lambda scene, **kw: scene.render(spp=1).save(**kw), {
            "scene": scene, "path": Arg(paths, bad_paths, False), "image": Arg(IMAGES)}),
        "RenderResult.properties": (lambda scene: _result_fields(scene.render(spp=1)), {"scene": scene}),
        "warp_names": (lambda **kw: penumbra.warp_names(**kw), {"junk": Arg([], [1])}),
        "axes": (lambda **kw: penumbra.axes(**kw), {"junk": Arg([], [1])}),
        "samplers": (lambda **kw: penumbra.samplers(**kw), {"junk": Arg([], [1])}),
        "random_points": (penumbra.random_points, {
            "n": Arg([0, 1, 16, 1000], [-1, 2**40 + 1, 2**40, 2**64, 1.5, NAN], False),
            "seed": Arg([0, 1, 2**63 - 1, 2**64 - 1], INT_EDGES),
            "out": Arg([None, Fresh(lambda: np.empty((16, 2), np.float32))], OUT_ARRAYS)}),
        "warp": (penumbra.warp, {
            "name": Arg(WARPS, ["", "x", "tent\x00", 3, None], False),
            "u": Arg(POINT_ARRAYS[:2], POINT_ARRAYS, False),
            "param": Arg([None, 0.5, 0.2, -1.0, 0.999], FLOAT_EDGES),
            "out": Arg([None], OUT_ARRAYS + ["alias"])}),
        "pdf": (penumbra.pdf, {
            "name": Arg(WARPS, ["", "x", 3], False),
            "v": Arg(POINT_ARRAYS[:4], POINT_ARRAYS, False),
            "param": Arg([None, 0.5, 0.2], FLOAT_EDGES),
            "out": Arg([None], OUT_ARRAYS + ["alias"])}),
        "chi2_test": (lambda **kw: _chi2_fields(penumbra.chi2_test(**kw)), {
            "name": Arg(WARPS, ["", "x", 3], False),
            "samples": Arg([100, 300, 2000], [99, 0, -1, 10**9 + 1, 10**9] + INT_EDGES),
            "seed": Arg([0, 1], INT_EDGES),
            "res": Arg([2, 5, 20, 1000], [1, 0, 1001, -1, 2**31]),
            "param": Arg([None, 0.5, 0.2], FLOAT_EDGES),
            "test_count": Arg([1, 5], [0, -1, 2**31, 2**64])}),
        "bsdf_names": (penumbra.bsdf_names, {}),
        "bsdf_sample": (penumbra.bsdf_sample, {
            "name": Arg(BSDFS, ["", "x", "diffuse", "microfacet\x00", 3, None], False),
            "u": Arg(POINT_ARRAYS[:2], POINT_ARRAYS, False),
            **BSDF_ARGS,
            "out": Arg([None], OUT_ARRAYS + ["alias"])}),
        "bsdf_pdf": (penumbra.bsdf_pdf, {
            "name": Arg(BSDFS, ["", "x", 3], False),
            "v": Arg(POINT_ARRAYS[:4], POINT_ARRAYS, False),
            **BSDF_ARGS,
            "out": Arg([None], OUT_ARRAYS + ["alias"])}),
        "bsdf_chi2_test": (lambda **kw: _chi2_fields(penumbra.bsdf_chi2_test(**kw)), {
            "name": Arg(BSDFS, ["", "x", 3], False),
            "samples": Arg([100, 300, 2000], [99, 0, -1, 10**9 + 1, 10**9] + INT_EDGES),
            "seed": Arg([0, 1], INT_EDGES),
            "res": Arg([2, 5, 20], [1, 0, 1001, -1, 2**31]),
            **BSDF_ARGS,
            "test_count": Arg([1, 5], [0, -1, 2**31, 2**64])}),
        "sample_points": (penumbra.sample_points, {
            "sampler": Arg(SAMPLERS, ["", "x", "all", 3], False),
            "n": Arg([1, 10, 100], [0, -1, 2**30 + 1, 2**64], False),
            "pixel": Arg([(0, 0), (3, 4), (2**31 - 1, 0)], [(-1, 0), (2**31, 0), (0,), "ab", None, (NAN, 0)]),
            "dims": Arg([(0, 1), (2, 3), (8190, 8191)], [(1, 2), (-2, -1), (8192, 8193), (0,), (2**62, 2**62 + 1)]),
            "seed": Arg([0, 1], INT_EDGES),
            "sample_count": Arg([None, 1, 64, 2**30], [0, -1, 2**30 + 1, 2**64])}),
        "converge": (lambda **kw: _converge_fields(penumbra.converge(**kw)), {
            "scene": Arg([Fresh(scene_factory)], [None, 3, "scene"], optional=False),
            "strategies": Arg(["all", "area", ["area", "solid-angle"]], [[], "", "nope", [3], (), ",", "area\x00"]),
            "samplers": Arg([None, "all", "independent", ["sobol", "stratified"]], [[], "", "nope", ["x"], 3]),
            "light_selection": Arg([None, "bvh", ["all", "power"]], [[], "", "nope", [3], "bvh\x00"]),
            "light_measure": Arg([None, "area"], [[], "nope", 3]),
            "heuristic": Arg([None, "balance", ["power", "balance"]], ["", "nope", [None]]),
            "time": Arg([None, 0.02], [NAN, INF, 0.0, -1.0, "1"]),
            "spp": Arg([1, 2], [0, 2**24 + 1, -1, 2**64]),
            "reference": Arg([tiny_ref], [None, "closed-form", "/nonexistent.exr", "", 3.0,
                                          Fresh(lambda: np.zeros((2, 2, 3))), Fresh(lambda: np.zeros((6, 8)))]),
            "seed": Arg([0, 1], [-1, 0x5EEDF00D12345678, 2**64]),
            "threads": Arg([None, 1, 2], [0, 1025])}),
        "closed_form.sphere_light_irradiance_factor": (penumbra.closed_form.sphere_light_irradiance_factor, {
            "cos_theta": Arg([0.5, -1.0, 1.0, Fresh(lambda: np.linspace(-1, 1, 5))],
                             FLOAT_EDGES + [1.5, Fresh(lambda: np.array([0.5, NAN]))], False),
            "sin_alpha": Arg([0.1, 0.0, 1.0], FLOAT_EDGES + [2.0], False)}),
        "closed_form.sphere_light_irradiance_factor_at":
            (penumbra.closed_form.sphere_light_irradiance_factor_at, {
                "x": Arg([[0, 0, 0], (1.0, 2.0, 3.0)], [[0, 0], [NAN, 0, 0], "abc", None], False),
                "n": Arg([[0, 0, 1], [1, 1, 1]], [[0, 0, 0], [INF, 0, 0]], False),
                "center": Arg([[0, 0, 2], [0, 0, 0.5]], [[0, 0, NAN]], False),
                "radius": Arg([1.0, 0.5], FLOAT_EDGES, False),
                "two_sided": Arg([False, True], [None, "yes"])}),
        "closed_form.ao_plane_with_sphere": (penumbra.closed_form.ao_plane_with_sphere, {
            "cos_theta": Arg([0.5, -0.2], FLOAT_EDGES, False), "sin_alpha": Arg([0.1, 0.9], FLOAT_EDGES, False)}),
        "closed_form.ao_plane_near_resting_sphere": (penumbra.closed_form.ao_plane_near_resting_sphere, {
            "rho": Arg([0.0, 1.0, 1e6], FLOAT_EDGES, False), "radius": Arg([1.0, 0.01], FLOAT_EDGES, False)}),
        "closed_form.ao_on_resting_convex_body": (penumbra.closed_form.ao_on_resting_convex_body, {
            "psi": Arg([0.0, 1.0, math.pi, Fresh(lambda: np.linspace(0, 3, 4))], FLOAT_EDGES, False)}),
    }


def _result_fields(r):
    assert r.mean.dtype == np.float32 and r.mean.shape == r.stderr.shape and r.mean.ndim == 3
    return (r.spp, r.seconds, r.samples, r.bad_samples, r.threads, r.metadata, repr(r))


def _chi2_fields(r):
    assert r.verdict in ("accept", "REJECT", "inconclusive")
    assert r.accepted == (r.verdict == "accept") and r.inconclusive == (r.verdict == "inconclusive")
    assert r.observed.shape == r.expected.shape and np.all(r.expected >= 0)
    return (r.warp, r.param, r.p_value, r.chi2, r.dof, r.alpha, r.message, r.pooled_cells, repr(r))


def _converge_fields(runs):
    for m in runs.values():
        assert len(m["spp"]) == len(m["mse"]) >= 1 and m["final_image"].ndim == 3
    return runs


def _draw(rng, arguments):
    """Keyword arguments: each one omitted (if optional), valid, hostile or of a wrong type."""
    kwargs, hostile = {}, rng.random() < 0.7
    for name, arg in arguments.items():
        roll = rng.random()
        if arg.optional and roll < 0.25:
            continue
        if hostile and roll > 0.75 and not arg.receiver:
            pool = arg.bad + (CONFUSION if rng.random() < 0.3 else [])
        else:
            pool = arg.good
        if not pool:
            continue
        value = rng.choice(pool)
        kwargs[name] = value.make() if isinstance(value, Fresh) else value
    # "alias": an output overlapping the input; "out"/"image": a str where an array goes.
    for key, source in (("out", "u"), ("out", "v")):
        alias = isinstance(kwargs.get(key), str) and kwargs[key] == "alias"
        if alias and isinstance(kwargs.get(source), np.ndarray) and kwargs[source].size:
            kwargs[key] = kwargs[source]
    return kwargs


def _public_names():
    names = {n for n in dir(penumbra) if not n.startswith("_")}
    names |= {"closed_form." + n for n in dir(penumbra.closed_form) if not n.startswith("_")}
    return names - {"SceneError", "Scene", "RenderResult", "Chi2Result", "closed_form"}


def test_the_campaign_covers_every_public_function(tmp_path):
    covered = {name.split(".")[0] if name.startswith(("Scene", "Render")) else name for name in specs(tmp_path)}
    assert _public_names() <= covered


def test_fuzz_campaign(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # converge(reference=None) caches its reference beside a string scene: here
    seed = int(os.environ.get("PENUMBRA_FUZZ_SEED", "1"))
    budget_calls = int(os.environ.get("PENUMBRA_FUZZ_CALLS", "300"))
    budget_seconds = float(os.environ.get("PENUMBRA_FUZZ_SECONDS", "20"))
    rng = random.Random(seed)
    table = specs(tmp_path)
    names = sorted(table)
    armed = [False]

    def on_alarm(signum, frame):
        if armed[0]:
            raise CallTimeout()

    previous = signal.signal(signal.SIGALRM, on_alarm)
    # A call that ignores the alarm altogether (a hang without signal checks) ends the whole run here,
    # with every thread's stack.
    faulthandler.dump_traceback_later(CALL_SECONDS + 60, repeat=True, exit=True)
    problems, counts, outcomes = [], {}, {}
    deadline = time.monotonic() + budget_seconds
    caught = warnings.catch_warnings()  # numpy's ComplexWarning and the like are not findings
    caught.__enter__()
    warnings.simplefilter("ignore")
    try:
        calls = 0
        while calls < budget_calls and time.monotonic() < deadline:
            calls += 1
            name = names[(calls - 1) % len(names)] if calls <= len(names) else rng.choice(names)
            function, arguments = table[name]
            kwargs = _draw(rng, arguments)
            counts[name] = counts.get(name, 0) + 1
            shown = f"call {calls} (seed {seed}): {name}({', '.join(f'{k}={v!r:.80}' for k, v in kwargs.items())})"
            started = time.monotonic()
            armed[0] = True
            signal.setitimer(signal.ITIMER_REAL, CALL_SECONDS)
            try:
                function(**kwargs)
                armed[0] = False
                outcome = "returned"
            except CallTimeout:
                armed[0] = False
                outcome = "interrupted"
                over = time.monotonic() - started - CALL_SECONDS
                if over > STOP_SECONDS:
                    problems.append(f"{shown}: stopped {over:.2f} s after SIGALRM")
            except ALLOWED as e:
                armed[0] = False
                outcome = type(e).__name__
                if not str(e):
                    problems.append(f"{shown}: {type(e).__name__} without a message")
            except BaseException as e:  # noqa: B902 (anything else is a finding, KeyboardInterrupt too)
                armed[0] = False
                outcome = type(e).__name__
                problems.append(f"{shown}: {type(e).__name__}: {e}")
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
                armed[0] = False
            outcomes[outcome] = outcomes.get(outcome, 0) + 1
    finally:
        caught.__exit__(None, None, None)
        faulthandler.cancel_dump_traceback_later()
        signal.signal(signal.SIGALRM, previous)
    print(f"fuzz: seed {seed}, {calls} calls, outcomes {outcomes}, per function {counts}")
    assert not problems, "\n".join(problems)
    assert len(counts) == len(names) or calls == budget_calls or time.monotonic() >= deadline
