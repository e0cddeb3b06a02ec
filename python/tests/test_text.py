"""Text across the boundary: scene bytes that are not UTF-8 are a SceneError with file and line; every
string the module returns is str; NUL characters and empty paths in arguments are ValueErrors; paths
may be str, bytes or os.PathLike."""
import os

import numpy as np
import pytest

import penumbra
from conftest import TINY_SCENE

LATIN1_SCENE = TINY_SCENE.replace("<scene>", "<scene>\n  <!-- caf\xe9 -->", 1).encode("latin-1")


def test_latin1_scene_file_names_file_and_line(tmp_path):
    path = tmp_path / "latin1.xml"
    path.write_bytes(LATIN1_SCENE)
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.load_scene(path)
    e = info.value
    assert e.file == str(path) and e.line == 2
    assert e.message.startswith("byte 0xE9 at column 11 is not UTF-8")
    assert not isinstance(e, UnicodeError)


def test_scene_text_that_is_not_utf8_or_has_a_nul_names_its_line():
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.scene_from_string(LATIN1_SCENE, name="inline.xml")  # bytes are passed through as they are
    assert info.value.file == "inline.xml" and info.value.line == 2
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.scene_from_string("<scene>\n\x00\n</scene>", name="nul.xml")
    assert info.value.file == "nul.xml" and info.value.line == 2 and "NUL" in info.value.message


def test_every_string_of_a_loaded_scene_is_text(tmp_path):
    # UTF-8 names (an unused property, a directory) come back as str, not UnicodeDecodeError.
    folder = tmp_path / "sc\u00e8nes \u2603"
    folder.mkdir()
    scene_path = folder / "tiny.xml"
    scene_path.write_text(TINY_SCENE.replace('<bsdf type="diffuse"/>',
                                             '<bsdf type="diffuse"><string name="caf\u00e9" value="\u2603"/></bsdf>'),
                          encoding="utf-8")
    scene = penumbra.load_scene(scene_path)
    assert scene.path == str(scene_path)
    assert any("caf\u00e9" in w for w in scene.warnings), scene.warnings
    assert "\u2603" in scene.to_xml() and "\u2603" in repr(scene)
    result = scene.render(spp=1)
    assert result.metadata["scene"] == str(scene_path)


def test_a_path_that_is_not_utf8_round_trips(tmp_path):
    raw = os.fsencode(tmp_path) + b"/latin1-\xe9.xml"
    with open(raw, "w") as f:
        f.write(TINY_SCENE)
    scene = penumbra.load_scene(raw)
    assert scene.path == os.fsdecode(raw) and os.fsencode(scene.path) == raw
    scene.render(spp=1).save(os.fsdecode(raw) + ".pfm")
    assert os.path.exists(raw + b".pfm")
    with pytest.raises(penumbra.SceneError) as info:
        penumbra.load_scene(raw + b".missing")
    assert info.value.file == os.fsdecode(raw + b".missing")


@pytest.mark.parametrize("path", ["", b"", "scene\x00.xml", b"scene\x00.xml"])
def test_empty_paths_and_nul_characters_are_value_errors(path):
    with pytest.raises(ValueError, match="path"):
        penumbra.load_scene(path)
    result = penumbra.scene_from_string(TINY_SCENE).render(spp=1)
    with pytest.raises(ValueError, match="path"):
        result.save(path)


def test_paths_may_be_path_objects(tmp_path):
    target = tmp_path / "tiny.xml"
    target.write_text(TINY_SCENE)
    scene = penumbra.load_scene(target)
    scene.render(spp=1).save(tmp_path / "out.exr")
    assert (tmp_path / "out.exr").stat().st_size > 0
    with pytest.raises(TypeError, match="path: expected a str, bytes or os.PathLike"):
        penumbra.load_scene(3)


def test_nul_characters_in_other_strings_are_value_errors():
    scene = penumbra.scene_from_string(TINY_SCENE)
    with pytest.raises(ValueError, match="key"):
        scene.set("sampler.sample\x00Count", 4)
    with pytest.raises(ValueError, match="value"):
        scene.set("integrator.measure", "area\x00junk")
    with pytest.raises(ValueError, match="overrides"):
        penumbra.scene_from_string(TINY_SCENE, overrides={"sampler.sample\x00Count": 4})
    with pytest.raises(ValueError, match="name"):
        penumbra.scene_from_string(TINY_SCENE, name="a\x00b")
    with pytest.raises(ValueError, match="name"):
        penumbra.warp("tent\x00", np.zeros((1, 2)))
    with pytest.raises(ValueError, match="sampler"):
        penumbra.sample_points("independent\x00", 4)
    with pytest.raises(ValueError, match="strategies"):
        penumbra.converge(scene, strategies="area\x00", spp=1, reference=np.zeros((12, 16, 3)))
    assert scene.sample_count == 2  # unchanged


def test_text_that_cannot_be_utf8_is_a_value_error():
    # A str with a lone surrogate has no UTF-8 form; bytes that are not UTF-8 are quoted as \xNN.
    scene = penumbra.scene_from_string(TINY_SCENE)
    with pytest.raises(ValueError, match="not valid text"):
        scene.set("integrator.measure", "\udcff")
    with pytest.raises(ValueError, match="overrides: not valid text"):
        penumbra.scene_from_string(TINY_SCENE, overrides={"\udcff": 1})
    with pytest.raises(ValueError, match=r"name: unknown warp '\\xFF\\xFE'"):
        penumbra.warp(b"\xff\xfe", np.zeros((1, 2)))
    with pytest.raises(ValueError, match=r"sampler: unknown sampler '\\xFF'"):
        penumbra.sample_points(b"\xff", 4)
    # As a path, a surrogate escape is the byte it stands for (os.fsencode).
    assert penumbra.scene_from_string(TINY_SCENE, base_dir="\udcff").width == 16
