"""Shared fixtures: where the source tree and the penumbra CLI are (ctest sets both)."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("PENUMBRA_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("PENUMBRA_BINARY", SOURCE_DIR / "build" / "penumbra"))
SPHERE_SCENE = SOURCE_DIR / "scenes" / "hw2" / "Tests" / "sphere-solid.xml"

# A small scene (sphere on a plane lit by a sphere light, no files): renders in milliseconds.
TINY_SCENE = """<scene>
  <sampler type="independent"><integer name="sampleCount" value="2"/></sampler>
  <integrator type="direct"><string name="measure" value="solid-angle"/></integrator>
  <shape type="sphere"><point name="center" value="1,-1.5,1.75"/><float name="radius" value="0.1"/>
    <emitter type="area"><color name="radiance" value="300,300,300"/></emitter></shape>
  <shape type="sphere"><point name="center" value="0,0,0"/><float name="radius" value="1"/>
    <bsdf type="diffuse"/></shape>
  <camera type="perspective">
    <transform name="toWorld"><lookat target="0,0,0" origin="5,0,2" up="0,0,1"/></transform>
    <float name="fov" value="30"/><integer name="width" value="16"/><integer name="height" value="12"/>
  </camera>
</scene>"""


def child_env(**extra):
    """The environment of a child interpreter that imports this same module from any directory."""
    import penumbra
    module_dir = os.path.dirname(os.path.abspath(penumbra.__file__))
    path = os.pathsep.join(p for p in (module_dir, os.environ.get("PYTHONPATH", "")) if p)
    return {**os.environ, "PYTHONPATH": path, **extra}


@pytest.fixture
def cli():
    """Runs the penumbra CLI; returns the CompletedProcess (text)."""
    if not BINARY.exists():
        pytest.skip(f"{BINARY} not built")

    def run(*args, stdin=None, check=True):
        return subprocess.run([str(BINARY), *map(str, args)], input=stdin, capture_output=True, text=True,
                              check=check)

    return run
