"""Convergence measurements and closed forms."""
import math
import subprocess
import sys

import numpy as np
import pytest

import penumbra
from conftest import SOURCE_DIR, SPHERE_SCENE

ANALYTIC = sorted((SOURCE_DIR / "scenes" / "analytic").glob("*.xml"))


def test_converge_returns_the_csv_columns():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"camera.width": 48, "camera.height": 32})
    ref = scene.render(spp=256, seed=99).mean
    runs = penumbra.converge(scene, strategies=["area", "solid-angle"], spp=16, reference=ref)
    assert list(runs) == ["area", "solid-angle"]
    for m in runs.values():
        for column in ("seconds", "cpu_seconds", "spp", "samples", "mse", "rmse", "rel_mse", "mse_stderr",
                       "ref_variance", "mse_nolight", "rmse_nolight", "rel_mse_nolight", "mse_stderr_nolight"):
            assert isinstance(m[column], np.ndarray) and len(m[column]) == len(m["spp"]) >= 2
        assert m["spp"][-1] == 16 and np.all(np.diff(m["spp"]) > 0)
        assert m["final_image"].shape == (32, 48, 3)
    # Solid-angle sampling beats area sampling for this small light.
    assert runs["solid-angle"]["mse_nolight"][-1] < runs["area"]["mse_nolight"][-1]


def test_converge_crosses_the_axes():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"camera.width": 12, "camera.height": 8})
    ref = np.zeros((8, 12, 3))
    runs = penumbra.converge(scene, strategies="area,mis", light_selection=["all", "bvh"],
                             heuristic="power,balance", spp=1, reference=ref)
    assert list(runs) == ["area", "area-bvh", "mis-solid-angle-power", "mis-solid-angle-balance"]
    with pytest.warns(DeprecationWarning, match="--strategies area --light-selection bvh"):
        old = penumbra.converge(scene, strategies="area-bvh", spp=1, reference=ref)
    assert list(old) == ["area-bvh"]
    with pytest.raises(ValueError, match="light_selection: unknown light selection"):
        penumbra.converge(scene, strategies="area", light_selection="nope", spp=1, reference=ref)


def test_converge_with_samplers():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"camera.width": 24, "camera.height": 16})
    ref = scene.render(spp=64, seed=99).mean
    names = [s["name"] for s in penumbra.samplers()]
    runs = penumbra.converge(scene, strategies="solid-angle", samplers=names, spp=4, reference=ref)
    assert set(runs) == {("solid-angle", n) for n in names}
    with pytest.raises(ValueError, match="samplers"):
        penumbra.converge(scene, strategies="solid-angle", samplers=["nope"], spp=4, reference=ref)
    with pytest.raises(ValueError, match="time or spp"):
        penumbra.converge(scene, reference=ref)
    with pytest.raises(ValueError, match="reference"):
        penumbra.converge(scene, spp=1, reference=np.zeros((2, 2, 3), np.float32))


@pytest.mark.skipif(not ANALYTIC, reason="no analytic scenes")
def test_converge_against_closed_form_reference():
    scene = penumbra.load_scene(str(ANALYTIC[0]))
    runs = penumbra.converge(scene, strategies="solid-angle", spp=4, reference="closed-form")
    assert runs["solid-angle"]["rmse"][-1] > 0


def _small_sphere_scene():
    scene = penumbra.load_scene(str(SPHERE_SCENE), overrides={"camera.width": 24, "camera.height": 16})
    return scene, scene.render(spp=16, seed=99).mean


def test_converge_refuses_empty_strategy_and_sampler_lists():
    # An empty list would otherwise mean the default: every strategy, or the scene's sampler.
    scene, ref = _small_sphere_scene()
    for empty in ([], "", (), ",", " "):
        with pytest.raises(ValueError, match="strategies: expected 'all' or at least one name"):
            penumbra.converge(scene, strategies=empty, spp=1, reference=ref)
        with pytest.raises(ValueError, match="samplers: expected 'all' or at least one name"):
            penumbra.converge(scene, strategies="area", samplers=empty, spp=1, reference=ref)
    with pytest.raises(TypeError, match="strategies"):
        penumbra.converge(scene, strategies=["area", 3], spp=1, reference=ref)


def test_converge_refuses_empty_axis_lists_naming_the_axis_values():
    # 'all' is no axis's "every value", so the message offers the names only.
    scene, ref = _small_sphere_scene()
    expected = {"light_selection": "all, uniform, power, bvh", "light_measure": "area, solid-angle",
                "heuristic": "power, balance"}
    for argument in expected:
        for empty in ([], "", ","):
            with pytest.raises(ValueError) as info:
                penumbra.converge(scene, strategies="mis", spp=1, reference=ref, **{argument: empty})
            message = str(info.value)
            assert message.startswith(f"{argument}: expected at least one of "), message
            assert message.endswith(", got none") and "'all' or" not in message, message
            assert expected[argument] in message, message
    for argument in ("light_measure", "heuristic"):  # and 'all' is refused there, naming the values
        with pytest.raises(ValueError, match=f"{argument}: unknown"):
            penumbra.converge(scene, strategies="mis", spp=1, reference=ref, **{argument: "all"})
    with pytest.raises(ValueError, match="strategies: unknown strategy"):
        penumbra.converge(scene, strategies="nope", spp=1, reference=ref)


def test_converge_accepts_samplers_all_as_the_cli_does():
    scene, ref = _small_sphere_scene()
    runs = penumbra.converge(scene, strategies="area", samplers="all", spp=2, reference=ref)
    assert list(runs) == [("area", s["name"]) for s in penumbra.samplers()]
    assert all(m["sampler"] == name for (_, name), m in runs.items())


@pytest.mark.parametrize("time", [math.inf, -math.inf, math.nan, 0.0, -1.0])
def test_converge_time_is_checked_as_the_cli_checks_it(time):
    scene, ref = _small_sphere_scene()
    with pytest.raises(ValueError, match=r"^time: expected a finite number > 0, got "):
        penumbra.converge(scene, strategies="area", time=time, reference=ref)


@pytest.mark.parametrize("call", [
    lambda v: penumbra.closed_form.sphere_light_irradiance_factor(v, 0.5),
    lambda v: penumbra.closed_form.sphere_light_irradiance_factor(0.5, v),
    lambda v: penumbra.closed_form.sphere_light_irradiance_factor(np.array([0.5, v]), 0.5),
    lambda v: penumbra.closed_form.ao_plane_with_sphere(v, 0.5),
    lambda v: penumbra.closed_form.ao_plane_near_resting_sphere(v, 1.0),
    lambda v: penumbra.closed_form.ao_plane_near_resting_sphere(1.0, v),
    lambda v: penumbra.closed_form.ao_on_resting_convex_body(v),
    lambda v: penumbra.closed_form.sphere_light_irradiance_factor_at([0, 0, v], [0, 0, 1], [0, 0, 2], 1.0),
    lambda v: penumbra.closed_form.sphere_light_irradiance_factor_at([0, 0, 0], [0, 0, 1], [0, 0, 2], v),
])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_closed_forms_refuse_non_finite_arguments(call, value):
    with pytest.raises(ValueError, match="expected a finite number"):
        call(value)


def test_closed_forms_refuse_arguments_outside_their_domain():
    cf = penumbra.closed_form
    with pytest.raises(ValueError, match="cos_theta"):
        cf.sphere_light_irradiance_factor(1.5, 0.5)
    with pytest.raises(ValueError, match="sin_alpha"):
        cf.ao_plane_with_sphere(0.5, -0.5)
    with pytest.raises(ValueError, match="radius"):
        cf.ao_plane_near_resting_sphere(1.0, 0.0)
    with pytest.raises(ValueError, match="rho"):
        cf.ao_plane_near_resting_sphere(-1.0, 1.0)
    with pytest.raises(ValueError, match="radius"):
        cf.sphere_light_irradiance_factor_at([0, 0, 0], [0, 0, 1], [0, 0, 2], -1.0)
    with pytest.raises(ValueError, match="n: expected a non-zero normal"):
        cf.sphere_light_irradiance_factor_at([0, 0, 0], [0, 0, 0], [0, 0, 2], 1.0)
    with pytest.raises(ValueError):  # shapes that do not broadcast, as for a ufunc
        cf.sphere_light_irradiance_factor(np.zeros(5), [0.1, 0.2])
    with pytest.raises(TypeError):
        cf.ao_on_resting_convex_body("half a turn")
    # Rounding past the domain's edge (a cosine from a dot product) is not an error.
    assert cf.sphere_light_irradiance_factor(1.0 + 2e-16, 0.5) == pytest.approx(math.pi * 0.25)


def test_closed_forms():
    cf = penumbra.closed_form
    # Fully above the horizon: pi sin^2(alpha) cos(theta).
    assert cf.sphere_light_irradiance_factor(1.0, 0.5) == pytest.approx(math.pi * 0.25)
    assert cf.sphere_light_irradiance_factor(-1.0, 0.5) == 0.0
    v = cf.sphere_light_irradiance_factor(np.array([1.0, 0.5]), 0.1)
    assert v.shape == (2,) and v[1] == pytest.approx(math.pi * 0.01 * 0.5)
    assert cf.sphere_light_irradiance_factor_at([0, 0, 0], [0, 0, 1], [0, 0, 2], 1.0) == pytest.approx(
        math.pi * 0.25)
    assert cf.ao_on_resting_convex_body(0.0) == 1.0
    assert cf.ao_on_resting_convex_body(math.pi) == pytest.approx(0.0, abs=1e-15)
    rho = np.array([0.0, 1.0, 10.0])
    assert np.allclose(cf.ao_plane_near_resting_sphere(rho, 1.0), 1 - 1 / (rho ** 2 + 1) ** 1.5)
    assert cf.ao_plane_with_sphere(1.0, 0.5) == pytest.approx(1 - 0.25)


@pytest.mark.parametrize("script", ["compare_strategies.py", "warp_histogram.py"])
def test_examples_write_pngs(tmp_path, script):
    path = SOURCE_DIR / "python" / "examples" / script
    subprocess.run([sys.executable, str(path), "--quick", "-o", str(tmp_path / "out.png")], check=True,
                   env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    png = (tmp_path / "out.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000
