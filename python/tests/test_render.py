"""Scenes and rendering: CLI-identical images, arrays that own their pixels, errors, Ctrl-C, leaks."""
import gc
import os
import signal
import threading
import time

import numpy as np
import pytest

import penumbra
from conftest import SOURCE_DIR, SPHERE_SCENE, TINY_SCENE

SMALL = {"camera.width": 96, "camera.height": 64}


def test_render_matches_cli_pfm_bytes(cli, tmp_path):
    cli_out = tmp_path / "cli.pfm"
    cli("render", SPHERE_SCENE, "--set", "camera.width=96", "--set", "camera.height=64", "--spp", 8,
        "--seed", 7, "--threads", 2, "-o", cli_out)
    result = penumbra.load_scene(str(SPHERE_SCENE), overrides=SMALL).render(spp=8, seed=7, threads=2)
    py_out = tmp_path / "py.pfm"
    result.save(str(py_out))
    assert result.spp == 8 and result.bad_samples == 0
    assert py_out.read_bytes() == cli_out.read_bytes()
    # A different seed gives different bytes: the comparison can fail.
    penumbra.load_scene(str(SPHERE_SCENE), overrides=SMALL).render(spp=8, seed=8, threads=2).save(str(py_out))
    assert py_out.read_bytes() != cli_out.read_bytes()


def test_save_writes_every_format(tmp_path):
    result = penumbra.scene_from_string(TINY_SCENE).render(spp=2)
    for ext in ("exr", "pfm", "png"):
        result.save(str(tmp_path / f"out.{ext}"))
        assert (tmp_path / f"out.{ext}").stat().st_size > 0
    with pytest.raises(penumbra.SceneError):
        result.save(str(tmp_path / "out.bmp"))


def test_arrays_are_owned_writeable_float32():
    scene = penumbra.scene_from_string(TINY_SCENE)
    result = scene.render(spp=4, seed=1)
    del scene
    gc.collect()
    for a in (result.mean, result.stderr):
        assert isinstance(a, np.ndarray) and a.dtype == np.float32 and a.shape == (12, 16, 3)
        assert a.flags.writeable and a.flags.c_contiguous
    assert np.isfinite(result.mean).all() and result.mean.max() > 0
    mean = result.mean
    del result
    gc.collect()
    mean[0, 0] = 1.5  # still valid memory after the result is gone
    assert mean[0, 0, 0] == 1.5 and mean.sum() > 0


def test_settings_read_and_set():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"integrator.measure": "area", **SMALL})
    assert scene.strategy == "direct/area" and scene.width == 96 and scene.height == 64
    scene.set("sampler.sampleCount", 64)
    assert scene.sample_count == 64 and scene.settings["sampleCount"] == "64"
    scene.set("integrator.measure", "solid-angle")
    assert scene.strategy == "direct/solid-angle"
    assert scene.render().spp == 64  # the scene's sampleCount by default
    with pytest.raises(penumbra.SceneError):
        scene.set("integrator.measure", "nonsense")
    assert scene.strategy == "direct/solid-angle"  # unchanged after the error
    scene.set("integrator.lightSelection", "bvh")
    assert scene.axes == {"integrator": "direct", "measure": "solid-angle", "light_selection": "bvh"}
    scene.set("integrator.measure", "mis")
    assert scene.axes == {"integrator": "direct", "measure": "mis", "light_measure": "solid-angle",
                          "heuristic": "power"}
    with pytest.raises(TypeError, match="value"):
        scene.set("sampler.sampleCount", [1])


def test_to_xml_reads_back_to_the_same_scene():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides=SMALL)
    scene.set("integrator.measure", "area")
    scene.set("sampler.seed", 5)
    xml = scene.to_xml()
    # The core scene writer: canonical spellings, the camera's <lookat> kept.
    assert 'name="measure" value="area"' in xml and "<lookat" in xml
    again = penumbra.scene_from_string(xml, base_dir=str(SPHERE_SCENE.parent))
    assert again.settings == scene.settings
    assert again.to_xml() == xml


def test_scene_error_carries_file_and_line(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("<scene>\n  <sampler type=\"independent\">\n    <integer name=\"sampleCount\" value=\"x\"/>\n"
                   "  </sampler>\n</scene>\n")
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.load_scene(str(bad))
    e = info.value
    assert isinstance(e, ValueError)
    assert e.file == str(bad) and e.line == 3
    assert "sampleCount" in e.message and str(e).startswith(f"{bad}:3: ")
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.scene_from_string("<scene>\n<bogus/>\n</scene>", name="inline.xml")
    assert info.value.file == "inline.xml" and info.value.line == 2


def test_bad_arguments_name_the_argument():
    scene = penumbra.scene_from_string(TINY_SCENE)
    for kwargs, name in (({"spp": 0}, "spp"), ({"time": -1.0}, "time"), ({"threads": 0}, "threads"),
                         ({"seed": -1}, "seed")):
        with pytest.raises(ValueError, match=name):
            scene.render(**kwargs)
    with pytest.raises(TypeError, match="progress"):
        scene.render(spp=1, progress=3)
    with pytest.raises(TypeError, match="overrides"):
        penumbra.load_scene(str(SPHERE_SCENE), overrides=["camera.width=4"])


@pytest.mark.parametrize("time", [float("inf"), float("nan"), float("-inf"), 0.0, -2.5])
def test_render_time_is_checked_as_the_cli_checks_it(cli, tmp_path, time):
    # render(time=inf) would never end; the CLI refuses it with the same words.
    scene = penumbra.scene_from_string(TINY_SCENE)
    with pytest.raises(ValueError, match=r"^time: expected a finite number > 0, got "):
        scene.render(time=time)
    done = cli("render", SPHERE_SCENE, f"--time={time!r}", "-o", tmp_path / "out.exr", check=False)
    assert done.returncode == 2 and "expected a finite number > 0, got '" in done.stderr, done.stderr


def test_progress_callback_sees_every_pass():
    seen = []
    result = penumbra.scene_from_string(TINY_SCENE).render(spp=5, progress=lambda spp, s: seen.append(spp))
    assert seen[-1] == result.spp == 5 and seen == sorted(seen)


def test_progress_callback_exception_stops_the_render():
    def stop(spp, seconds):
        raise RuntimeError("enough")

    scene = penumbra.load_scene(str(SPHERE_SCENE))
    with pytest.raises(RuntimeError, match="enough"):
        scene.render(spp=100000, progress=stop)


def test_keyboard_interrupt_within_a_pass_leaves_process_usable():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"integrator.nSamples": 64})
    one_pass = scene.render(spp=1).seconds  # seconds of one pass (64 shadow rays per pixel)
    main = threading.main_thread().ident
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        signal.pthread_kill(main, signal.SIGINT)

    timer = threading.Timer(0.3, interrupt)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(spp=100000)
    latency = time.monotonic() - sent[0]
    timer.join()
    assert latency < one_pass, f"interrupt took {latency:.3f} s, a pass {one_pass:.3f} s"
    result = penumbra.scene_from_string(TINY_SCENE).render(spp=2)
    assert result.spp == 2 and np.isfinite(result.mean).all()
    assert scene.render(spp=1).spp == 1  # the interrupted scene renders again


def _rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_no_leak_over_1000_renders():
    scene = penumbra.scene_from_string(TINY_SCENE)
    for _ in range(100):  # warm up allocator pools
        scene.render(spp=1, threads=1)
    gc.collect()
    before = _rss_bytes()
    for i in range(1000):
        r = scene.render(spp=1, threads=1, seed=i)
        assert r.mean.shape == (12, 16, 3)
    del r
    gc.collect()
    grown = _rss_bytes() - before
    # 1000 leaked results would be >= 4.6 MB of pixels alone (plus engines and films).
    assert grown < 2 * 1024 * 1024, f"RSS grew by {grown} bytes"


def test_tables_are_listed():
    axes = penumbra.axes()
    assert set(axes) == {"integrator", "measure", "warp", "light_selection", "light_measure", "heuristic"}
    measures = [row["name"] for row in axes["measure"]]
    assert measures == ["hemisphere", "bsdf", "area", "solid-angle", "projected-solid-angle", "mis"]
    assert [row["name"] for row in axes["light_selection"]] == ["all", "uniform", "power", "bvh"]
    assert "solidAngle" in axes["light_measure"][1]["aliases"]
    for rows in axes.values():
        names = [row["name"] for row in rows]
        assert len(names) == len(set(names)) and all(row["description"] for row in rows)
    names = [s["name"] for s in penumbra.samplers()]
    assert names[0] == "independent" and "stratified" in names


def test_help_shows_docstrings():
    assert "spp" in penumbra.Scene.render.__doc__ and "KeyboardInterrupt" in penumbra.Scene.render.__doc__
    assert "overrides" in penumbra.load_scene.__doc__


def test_glossy_scene_renders_as_the_cli_renders_it(cli, tmp_path):
    # Veach's scene (Beckmann roughconductor plates): Python's image is the CLI's, byte for byte, for
    # BSDF sampling and for MIS, and the two estimators agree in mean.
    veach = SOURCE_DIR / "scenes" / "veach-mis.xml"
    means = {}
    for measure in ("bsdf", "mis"):
        cli_out = tmp_path / f"cli-{measure}.pfm"
        cli("render", veach, "--set", "camera.width=48", "--set", "camera.height=32", "--set",
            f"integrator.measure={measure}", "--spp", 16, "--seed", 3, "--threads", 2, "-o", cli_out)
        scene = penumbra.load_scene(str(veach), overrides={"camera.width": 48, "camera.height": 32,
                                                           "integrator.measure": measure})
        result = scene.render(spp=16, seed=3, threads=2)
        assert result.bad_samples == 0
        py_out = tmp_path / f"py-{measure}.pfm"
        result.save(str(py_out))
        assert py_out.read_bytes() == cli_out.read_bytes()
        means[measure] = (float(result.mean.mean()), float(np.sqrt((result.stderr ** 2).sum()) / result.stderr.size))
    (m1, s1), (m2, s2) = means["bsdf"], means["mis"]
    assert abs(m1 - m2) < 5 * np.hypot(s1, s2) + 1e-6 * m2
