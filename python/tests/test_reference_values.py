"""converge refuses a reference holding an infinite or NaN value before anything renders, with the
count and the first value, whether the reference is an array, a RenderResult or a file."""
import numpy as np
import pytest

import penumbra
from conftest import TINY_SCENE


def small_scene():
    return penumbra.scene_from_string(TINY_SCENE)  # 16 x 12


@pytest.mark.parametrize("bad, shown", [(np.inf, "inf"), (np.nan, "nan")])
def test_array_reference_with_a_non_finite_value_is_refused(bad, shown):
    ref = np.full((12, 16, 3), 0.5, np.float32)
    ref[2, 3, 1] = bad  # pixel (x 3, y 2), channel G
    with pytest.raises(ValueError, match=rf"1 of 576 values is not finite; the first at pixel \(3, 2\) channel G: {shown}"):
        penumbra.converge(small_scene(), strategies="solid-angle", spp=2, reference=ref)


def test_negative_reference_values_are_allowed():
    ref = small_scene().render(spp=4, seed=9).mean
    ref[0, 0, 0] = -0.25  # what a pixel filter with negative lobes (mitchell) makes
    runs = penumbra.converge(small_scene(), strategies="solid-angle", spp=2, reference=ref)
    assert np.all(np.isfinite(runs["solid-angle"]["mse"]))


def test_render_result_with_a_negative_standard_error_is_refused():
    result = small_scene().render(spp=4, seed=9)
    result.stderr[11, 15, 2] = -1.0
    with pytest.raises(ValueError, match=r"\(standard error\): 1 of 576 values is not finite and non-negative; "
                                         r"the first at pixel \(15, 11\) channel B: -1"):
        penumbra.converge(small_scene(), strategies="solid-angle", spp=2, reference=result)


def test_file_reference_with_an_infinite_value_is_refused(tmp_path):
    result = small_scene().render(spp=4, seed=9)
    image = result.mean.copy()
    image[5, 7, 0] = np.inf
    path = tmp_path / "ref.exr"
    result.save(str(path), image)
    with pytest.raises(ValueError, match=r"ref\.exr: 1 of 576 values is not finite; the first at pixel \(7, 5\) "
                                         r"channel R: inf"):
        penumbra.converge(small_scene(), strategies="solid-angle", spp=2, reference=str(path))
