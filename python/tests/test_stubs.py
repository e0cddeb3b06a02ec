"""The stub file lists every public name the module has, and nothing it lacks."""
import ast
import pathlib

import penumbra

STUBS = pathlib.Path(__file__).resolve().parents[1] / "penumbra.pyi"


def test_stubs_cover_the_module():
    tree = ast.parse(STUBS.read_text())
    stubbed = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    public = {n for n in dir(penumbra) if not n.startswith("_")}
    assert stubbed == public
