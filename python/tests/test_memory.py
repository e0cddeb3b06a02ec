"""Running out of memory is an exception, never an abort: a render too large for what the process may
still allocate is refused first with the CLI's message (MemoryError), and so are huge arrays."""
import os
import subprocess
import sys

import numpy as np
import pytest

import penumbra
from conftest import BINARY, TINY_SCENE, child_env

# AddressSanitizer reserves terabytes of address space: an RLIMIT_AS would stop it, not the render.
UNDER_ASAN = "asan" in os.environ.get("LD_PRELOAD", "")
LIMIT = 1200 << 20  # bytes of address space: the interpreter and a 4096 x 4096 render do not fit

LOW_MEMORY = """
import resource
import penumbra
scene = penumbra.scene_from_string({tiny!r}, overrides={{"camera.width": 4096, "camera.height": 4096}})
resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))
try:
    scene.render(spp=1)
    print("rendered")
except MemoryError as e:
    print("MemoryError:", e)
"""


@pytest.mark.skipif(UNDER_ASAN, reason="an address-space limit stops AddressSanitizer itself")
def test_render_too_large_for_an_address_space_limit_raises_memory_error():
    done = subprocess.run([sys.executable, "-c", LOW_MEMORY.format(tiny=TINY_SCENE, limit=LIMIT)],
                          capture_output=True, text=True, timeout=300, env=child_env())
    assert done.returncode == 0, f"rc {done.returncode}: {done.stderr[-2000:]}"
    message = done.stdout.strip()
    assert message.startswith("MemoryError: render: a 4096x4096 render needs about 1.7 GB (108 B/pixel), only ")
    assert message.endswith(" available; lower camera width/height")


@pytest.mark.skipif(UNDER_ASAN or not BINARY.exists(), reason="needs the CLI, without AddressSanitizer")
def test_the_cli_says_the_same_under_the_same_limit(tmp_path):
    scene = tmp_path / "tiny.xml"
    scene.write_text(TINY_SCENE)
    limited = subprocess.run(
        ["bash", "-c", f'ulimit -v {LIMIT >> 10}; exec "$@"', "bash", str(BINARY), "render", str(scene), "--set",
         "camera.width=4096", "--set", "camera.height=4096", "--spp", "1", "-o", str(tmp_path / "out.exr")],
        capture_output=True, text=True, timeout=300)
    assert limited.returncode == 2, limited.stderr
    cli_words = limited.stderr.strip().removeprefix(f"error: {scene}: ")
    done = subprocess.run([sys.executable, "-c", LOW_MEMORY.format(tiny=TINY_SCENE, limit=LIMIT)],
                          capture_output=True, text=True, timeout=300, env=child_env())
    python_words = done.stdout.strip().removeprefix("MemoryError: render: ")
    # The same words up to the amount still available, which differs between the two processes.
    assert cli_words.split(", only ")[0] == python_words.split(", only ")[0], (cli_words, python_words)


def test_huge_arrays_are_memory_errors():
    with pytest.raises(MemoryError, match="random_points: the float32 result needs about 8192.0 GB"):
        penumbra.random_points(1 << 40)
    with pytest.raises(MemoryError):
        penumbra.warp("tent", np.broadcast_to(np.float32([0.5, 0.5]), (1 << 40, 2)))
