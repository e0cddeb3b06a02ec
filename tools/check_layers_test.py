#!/usr/bin/env python3
"""Shows that tools/check_layers.py can fail: runs it on small temporary trees, one clean and one per
kind of violation, and expects exit 0 for the clean tree and exit 1 naming the bad include otherwise.

Usage: tools/check_layers_test.py   (plain unittest, no pytest; ctest runs it as layer_order_self_test)
"""
import pathlib
import subprocess
import sys
import tempfile
import unittest

CHECK = pathlib.Path(__file__).resolve().parent / "check_layers.py"

# A tree that obeys every rule: each file includes only its own layer or lower ones.
CLEAN = {
    "core/math/vec.h": "#pragma once\n#include <cmath>\n",
    "core/geometry/ray.h": '#include "core/math/vec.h"\n',
    "core/render/film.cpp": '#include "core/render/film.h"\n#include "core/geometry/ray.h"\n',
    "core/render/film.h": '#include "core/math/vec.h"\n',
    "app/ui/panel.cpp": '#include <imgui.h>\n#include "app/platform/platform.h"\n#include "core/render/film.h"\n',
    "app/platform/platform.h": "#pragma once\n",
    "app/main.cpp": '#include "app/cli/commands.h"\n',
}


def run_check(files):
    with tempfile.TemporaryDirectory(prefix="check-layers-") as root:
        for rel, text in files.items():
            path = pathlib.Path(root) / rel
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        r = subprocess.run([sys.executable, str(CHECK), root], capture_output=True, text=True)
        return r.returncode, r.stdout + r.stderr


class CheckLayers(unittest.TestCase):
    def assertViolation(self, extra, expected):
        code, out = run_check({**CLEAN, **extra})
        self.assertEqual(code, 1, out)
        self.assertIn(expected, out)
        self.assertIn("1 violations", out)

    def test_clean_tree_passes(self):
        code, out = run_check(CLEAN)
        self.assertEqual(code, 0, out)
        self.assertIn("0 violations", out)

    def test_include_from_a_higher_core_layer_fails(self):
        self.assertViolation(
            {"core/render/engine_test.cpp": '#include "core/scene/scene_builder.h"\n'},
            "core/render/engine_test.cpp:1: includes core/scene/scene_builder.h: 'scene' is above 'render'",
        )

    def test_include_between_equal_rank_layers_fails(self):
        self.assertViolation(
            {"core/image/tonemap.cpp": '#include "core/sampling/rng.h"\n'},
            "core/image/tonemap.cpp:1: includes core/sampling/rng.h: 'sampling' sits beside 'image'",
        )

    def test_include_from_a_higher_app_layer_fails(self):
        self.assertViolation({"app/platform/window.cpp": '#include "app/ui/panels.h"\n'},
                             "'ui' is above 'platform'")

    def test_core_including_app_fails(self):
        self.assertViolation({"core/render/bad.cpp": '#include "app/ui/panels.h"\n'}, "core never includes app/")

    def test_core_including_imgui_or_gl_fails(self):
        self.assertViolation({"core/image/bad.cpp": "#include <imgui.h>\n"}, "core includes no GL or ImGui")
        self.assertViolation({"core/image/bad.cpp": "#include <GL/gl.h>\n"}, "core includes no GL or ImGui")

    def test_core_including_a_tests_fixture_fails(self):
        self.assertViolation({"core/image/io_test.cpp": '#include "tests/temp_dir_test.h"\n'},
                             "never includes tests/")

    def test_production_code_including_test_support_fails(self):
        self.assertViolation({"core/math/temp_dir_test_support.h": "#pragma once\n",
                              "core/math/files.cpp": '#include "core/math/temp_dir_test_support.h"\n'},
                             "core/math/files.cpp:1: includes core/math/temp_dir_test_support.h: only tests")

    def test_tests_and_test_support_may_include_test_support(self):
        code, out = run_check({**CLEAN, "core/math/temp_dir_test_support.h": "#pragma once\n",
                               "core/math/files_test.cpp": '#include "core/math/temp_dir_test_support.h"\n',
                               "core/render/render_test_support.h": '#include "core/math/temp_dir_test_support.h"\n'})
        self.assertEqual(code, 0, out)

    def test_directory_outside_the_order_fails(self):
        self.assertViolation({"core/extras/thing.h": "#pragma once\n"}, "has no place in the layer order")


if __name__ == "__main__":
    unittest.main()
