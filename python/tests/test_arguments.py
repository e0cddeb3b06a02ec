"""What a careful hostile user passes: NaN, infinities, negative, zero and huge numbers, wrong types,
empty strings, odd arrays. Every call raises a clear exception (ValueError, TypeError, SceneError,
MemoryError) naming what is wrong, and the module keeps working."""
import math

import numpy as np
import pytest

import penumbra
from conftest import TINY_SCENE

SCENE = penumbra.scene_from_string(TINY_SCENE)
RESULT = SCENE.render(spp=1)
REF = RESULT.mean
NAN, INF = math.nan, math.inf
U = penumbra.random_points(8, seed=1)
REFERENCE_SEED = 0x5EEDF00D12345678

# (label, call, exception, text the message contains)
BAD_CALLS = [
    ("render spp 0", lambda: SCENE.render(spp=0), ValueError, "spp: expected an integer in [1, 1073741824], got 0"),
    ("render spp huge", lambda: SCENE.render(spp=2**30 + 1), ValueError, "spp"),
    ("render spp negative", lambda: SCENE.render(spp=-5), ValueError, "spp"),
    ("render spp beyond int64", lambda: SCENE.render(spp=2**64), TypeError, ""),
    ("render spp float", lambda: SCENE.render(spp=1.5), TypeError, ""),
    ("render spp str", lambda: SCENE.render(spp="4"), TypeError, ""),
    ("render time str", lambda: SCENE.render(time="1"), TypeError, ""),
    ("render time huge int", lambda: SCENE.render(time=10**400), TypeError, ""),
    ("render seed negative", lambda: SCENE.render(seed=-1), ValueError, "seed"),
    ("render seed beyond uint64", lambda: SCENE.render(seed=2**64), ValueError,
     "seed: expected an integer in [0, 18446744073709551615], got 18446744073709551616"),
    ("render seed float", lambda: SCENE.render(seed=1.0), TypeError, ""),
    ("render threads 0", lambda: SCENE.render(threads=0), ValueError, "threads"),
    ("render threads 1025", lambda: SCENE.render(threads=1025), ValueError, "threads"),
    ("render threads huge", lambda: SCENE.render(threads=2**40), ValueError, "threads"),
    ("render progress str", lambda: SCENE.render(spp=1, progress="yes"), TypeError, "progress"),
    ("save empty image", lambda: RESULT.save("/tmp/x.pfm", np.zeros((0, 4, 3))), ValueError, "image"),
    ("save 2-D image", lambda: RESULT.save("/tmp/x.pfm", np.zeros((4, 3))), ValueError, "image"),
    ("save object image", lambda: RESULT.save("/tmp/x.pfm", np.full((2, 2, 3), "a", dtype=object)), TypeError,
     "image"),
    ("save unknown extension", lambda: RESULT.save("/tmp/x.bmp"), penumbra.SceneError, "bmp"),
    ("save into a directory that is missing", lambda: RESULT.save("/nonexistent-dir/x.pfm"), penumbra.SceneError,
     "nonexistent-dir"),
    ("save path int", lambda: RESULT.save(3), TypeError, "path"),
    ("set width huge", lambda: SCENE.set("camera.width", 10**30), penumbra.SceneError, "width"),
    ("set width 0", lambda: SCENE.set("camera.width", 0), penumbra.SceneError, "width"),
    ("set fov nan", lambda: SCENE.set("camera.fov", NAN), penumbra.SceneError, "fov"),
    ("set fov inf", lambda: SCENE.set("camera.fov", INF), penumbra.SceneError, "fov"),
    ("set empty key", lambda: SCENE.set("", 1), penumbra.SceneError, "object.property"),
    ("set key without a dot", lambda: SCENE.set("sampler", 1), penumbra.SceneError, "object.property"),
    ("set seed negative", lambda: SCENE.set("sampler.seed", -1), penumbra.SceneError,
     "seed must be an integer >= 0, got -1"),
    ("set value list", lambda: SCENE.set("camera.fov", [1]), TypeError, "value"),
    ("set value None", lambda: SCENE.set("camera.fov", None), TypeError, "value"),
    ("load missing file", lambda: penumbra.load_scene("/nonexistent/scene.xml"), penumbra.SceneError,
     "cannot open scene file"),
    ("load a directory", lambda: penumbra.load_scene("/tmp"), penumbra.SceneError, "/tmp"),
    ("load overrides list", lambda: penumbra.load_scene("/tmp", overrides=[("a", 1)]), TypeError, "overrides"),
    ("load overrides key int", lambda: penumbra.scene_from_string(TINY_SCENE, overrides={1: 2}), TypeError,
     "overrides"),
    ("empty scene text", lambda: penumbra.scene_from_string(""), penumbra.SceneError, "malformed XML"),
    ("unclosed scene", lambda: penumbra.scene_from_string("<scene>"), penumbra.SceneError, "malformed XML"),
    ("warp unknown name", lambda: penumbra.warp("", U), ValueError, "name: unknown warp ''"),
    ("warp param nan", lambda: penumbra.warp("beckmann", U, param=NAN), ValueError, "param"),
    ("warp param inf", lambda: penumbra.warp("uniform-cone", U, param=INF), ValueError, "param"),
    ("warp param negative alpha", lambda: penumbra.warp("beckmann", U, param=-1.0), ValueError, "param"),
    ("warp param for a warp without one", lambda: penumbra.warp("tent", U, param=0.5), ValueError, "param"),
    ("warp 3-D input", lambda: penumbra.warp("tent", np.zeros((3, 2, 1))), ValueError, "u"),
    ("warp 1 column", lambda: penumbra.warp("tent", np.zeros((3, 1))), ValueError, "u"),
    ("warp object input", lambda: penumbra.warp("tent", np.full((2, 2), "x", dtype=object)), TypeError, "u"),
    ("warp None input", lambda: penumbra.warp("tent", None), TypeError, "u"),
    ("warp read-only out", lambda: penumbra.warp("tent", U, out=_readonly((8, 2))), TypeError, "out"),
    ("warp strided out", lambda: penumbra.warp("tent", U, out=np.zeros((8, 4), np.float32)[:, ::2]), TypeError,
     "out"),
    ("warp out list", lambda: penumbra.warp("tent", U, out=[[0, 0]] * 8), TypeError, "out"),
    ("warp out wrong shape", lambda: penumbra.warp("tent", U, out=np.zeros((7, 2), np.float32)), ValueError,
     "out"),
    ("pdf 4 columns", lambda: penumbra.pdf("tent", np.zeros((3, 4))), ValueError, "v"),
    ("pdf param nan", lambda: penumbra.pdf("uniform-cone", np.zeros((3, 3)), param=NAN), ValueError, "param"),
    ("chi2 samples 99", lambda: penumbra.chi2_test("tent", samples=99), ValueError, "samples"),
    ("chi2 samples huge", lambda: penumbra.chi2_test("tent", samples=10**9 + 1), ValueError, "samples"),
    ("chi2 res 1", lambda: penumbra.chi2_test("tent", res=1), ValueError, "res"),
    ("chi2 res 1001", lambda: penumbra.chi2_test("tent", res=1001), ValueError, "res"),
    ("chi2 seed negative", lambda: penumbra.chi2_test("tent", seed=-1), ValueError, "seed"),
    ("chi2 seed beyond uint64", lambda: penumbra.chi2_test("tent", seed=2**64), ValueError, "seed"),
    ("chi2 test_count 0", lambda: penumbra.chi2_test("tent", test_count=0), ValueError, "test_count"),
    ("chi2 test_count huge", lambda: penumbra.chi2_test("tent", test_count=2**40), ValueError, "test_count"),
    ("chi2 param nan", lambda: penumbra.chi2_test("beckmann", param=NAN), ValueError, "param"),
    ("sample_points n 0", lambda: penumbra.sample_points("independent", 0), ValueError, "n"),
    ("sample_points n huge", lambda: penumbra.sample_points("independent", 2**30 + 1), ValueError, "n"),
    ("sample_points odd dims", lambda: penumbra.sample_points("independent", 4, dims=(1, 2)), ValueError, "dims"),
    ("sample_points far dims", lambda: penumbra.sample_points("independent", 4, dims=(8192, 8193)), ValueError,
     "dims"),
    ("sample_points negative pixel", lambda: penumbra.sample_points("independent", 4, pixel=(-1, 0)), ValueError,
     "pixel"),
    ("sample_points pixel beyond int", lambda: penumbra.sample_points("independent", 4, pixel=(2**31, 0)),
     ValueError, "pixel"),
    ("sample_points sample_count 0", lambda: penumbra.sample_points("stratified", 4, sample_count=0), ValueError,
     "sample_count"),
    ("sample_points empty sampler", lambda: penumbra.sample_points("", 4), ValueError, "sampler"),
    ("random_points n negative", lambda: penumbra.random_points(-1), ValueError, "n"),
    ("random_points seed negative", lambda: penumbra.random_points(4, seed=-1), ValueError, "seed"),
    ("random_points seed beyond uint64", lambda: penumbra.random_points(4, seed=2**64), ValueError, "seed"),
    ("sample_points seed negative", lambda: penumbra.sample_points("independent", 4, seed=-1), ValueError, "seed"),
    ("sample_points seed beyond uint64", lambda: penumbra.sample_points("independent", 4, seed=2**64), ValueError,
     "seed"),
    ("random_points out float64", lambda: penumbra.random_points(4, out=np.zeros((4, 2))), TypeError, "out"),
    ("converge spp 0", lambda: penumbra.converge(SCENE, spp=0, reference=REF), ValueError, "spp"),
    ("converge spp huge", lambda: penumbra.converge(SCENE, spp=2**24 + 1, reference=REF), ValueError, "spp"),
    ("converge no limit", lambda: penumbra.converge(SCENE, reference=REF), ValueError, "time or spp"),
    ("converge seed negative", lambda: penumbra.converge(SCENE, spp=1, seed=-1, reference=REF), ValueError,
     "seed"),
    ("converge seed beyond uint64", lambda: penumbra.converge(SCENE, spp=1, seed=2**64, reference=REF),
     ValueError, "seed"),
    ("converge reference seed", lambda: penumbra.converge(SCENE, spp=1, seed=REFERENCE_SEED, reference=REF),
     ValueError, "seed"),
    ("converge threads 0", lambda: penumbra.converge(SCENE, spp=1, threads=0, reference=REF), ValueError,
     "threads"),
    ("converge reference scalar", lambda: penumbra.converge(SCENE, spp=1, reference=3.0), ValueError,
     "reference"),
    ("converge reference wrong size", lambda: penumbra.converge(SCENE, spp=1, reference=np.zeros((2, 2, 3))),
     ValueError, "reference"),
    ("converge reference missing file", lambda: penumbra.converge(SCENE, spp=1, reference="/nonexistent.exr"),
     penumbra.SceneError, "nonexistent"),
    ("converge reference empty path", lambda: penumbra.converge(SCENE, spp=1, reference=""), ValueError,
     "reference"),
    ("converge scene None", lambda: penumbra.converge(None, spp=1, reference=REF), TypeError, ""),
]


def _readonly(shape):
    a = np.zeros(shape, np.float32)
    a.setflags(write=False)
    return a


@pytest.mark.parametrize("label,call,exception,words", BAD_CALLS, ids=[c[0] for c in BAD_CALLS])
def test_bad_arguments_raise_clear_exceptions(label, call, exception, words):
    with pytest.raises(exception) as info:
        call()
    assert words in str(info.value), f"{label}: {info.value!r}"


def test_the_module_still_works_after_every_bad_call():
    for _, call, exception, _ in BAD_CALLS:
        with pytest.raises(exception):
            call()
    assert SCENE.sample_count == 2 and SCENE.width == 16  # no failed set() changed the scene
    assert SCENE.render(spp=1).spp == 1


# Every function taking a seed, called with it: any 64-bit unsigned seed is taken, as by the CLI's --seed.
SEEDED = {
    "render": lambda seed: SCENE.render(spp=1, seed=seed).spp,
    "converge": lambda seed: len(penumbra.converge(SCENE, strategies="area", spp=1, seed=seed, reference=REF)),
    "chi2_test": lambda seed: penumbra.chi2_test("tent", samples=100, seed=seed).verdict,
    "sample_points": lambda seed: penumbra.sample_points("independent", 4, seed=seed).shape,
    "random_points": lambda seed: penumbra.random_points(4, seed=seed).shape,
}


@pytest.mark.parametrize("name", sorted(SEEDED))
def test_every_64_bit_seed_is_taken_and_nothing_beyond(name):
    call = SEEDED[name]
    for seed in (0, 2**63 - 1, 2**63, 2**64 - 1, np.uint64(2**64 - 1)):
        call(seed)
    for seed in (-1, 2**64, -2**64, 10**30):
        with pytest.raises(ValueError, match=r"^seed: expected an integer in \[0, 18446744073709551615\], got "):
            call(seed)


def test_the_largest_seed_is_not_clamped():
    assert not np.array_equal(penumbra.random_points(8, seed=2**64 - 1), penumbra.random_points(8, seed=2**63 - 1))
    assert not np.array_equal(SCENE.render(spp=1, seed=2**64 - 1).mean, SCENE.render(spp=1, seed=2**63 - 1).mean)


def test_non_finite_points_give_nan_not_garbage():
    u = np.array([[NAN, 0.5], [0.5, INF], [-INF, NAN], [0.25, 0.75]], np.float32)
    for name in penumbra.warp_names():
        v = penumbra.warp(name, u)
        assert np.isnan(v[:3]).all() and np.isfinite(v[3]).all(), name
        p = penumbra.pdf(name, v)
        assert np.isnan(p[:3]).all() and np.isfinite(p[3]), name
