#!/usr/bin/env python3
"""Fails when an include points up the layer order (docs/architecture.md, "Layers").

Core layers, bottom to top; a file may include its own layer and any layer below it:
  math < image, sampling < geometry < lights, materials < world < integrators < render < scene < analysis
App layers, bottom to top (every app layer may include all of core):
  platform, net < ui < cli < mpi
(net: streaming to the tev viewer over TCP; mpi: penumbra-mpi, the render shared by MPI ranks.) Layers of one rank sit beside each other (image and
sampling, platform and net) and include neither each other nor anything above them.
Core includes nothing from app/, no GL, GLFW, ImGui or OSMesa header; app/cli includes app/ui and
app/platform only in its GL-linked view and warp-gui commands, app/net in any command. Neither core/ nor app/ includes
anything from tests/: unit-test fixtures live beside the code they serve, named X_test_support.h, and
only tests (X_test.cpp, tests/) and other test support include them.

Usage: tools/check_layers.py [SOURCE_DIR]   (exit 0: clean, 1: violations listed, 2: bad usage)
"""
import pathlib
import re
import sys

CORE_RANK = {
    "math": 0,
    "image": 1,
    "sampling": 1,
    "geometry": 2,
    "lights": 3,
    "materials": 3,
    "world": 4,
    "integrators": 5,
    "render": 6,
    "scene": 7,
    "analysis": 8,
}
APP_RANK = {"platform": 0, "net": 0, "ui": 1, "cli": 2, "mpi": 3}
GRAPHICS = re.compile(r"^(GL/|GLFW/|imgui|GLES|EGL/|backends/imgui)")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def layer_of(rel: pathlib.PurePosixPath):
    """(area, layer) of a path like core/render/film.h, or None outside core/ and app/."""
    parts = rel.parts
    if len(parts) < 3 or parts[0] not in ("core", "app"):
        return None
    return parts[0], parts[1]


def check_file(root: pathlib.Path, path: pathlib.Path):
    rel = pathlib.PurePosixPath(path.relative_to(root).as_posix())
    if layer_of(rel) is None:  # app/main.cpp: the entry point sits above every layer
        return
    area, layer = layer_of(rel)
    ranks = CORE_RANK if area == "core" else APP_RANK
    if layer not in ranks:
        yield f"{rel}: directory '{area}/{layer}' has no place in the layer order (add it to {__file__})"
        return
    for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        target = m.group(2)
        where = f"{rel}:{number}: includes {target}"
        if GRAPHICS.match(target):
            if area == "core":
                yield f"{where}: core includes no GL or ImGui header"
            continue
        dest = layer_of(pathlib.PurePosixPath(target))
        is_test = rel.name.endswith("_test.cpp") or rel.name.endswith("_test_support.h")
        if target.endswith("_test_support.h") and not is_test:
            yield f"{where}: only tests include test support"
            continue
        if target.startswith("tests/"):
            yield f"{where}: {area}/ never includes tests/ (keep test fixtures beside their code)"
            continue
        if dest is None:
            continue
        dest_area, dest_layer = dest
        if area == "core" and dest_area == "app":
            yield f"{where}: core never includes app/"
        elif dest_area == area:
            if dest_layer not in ranks:
                yield f"{where}: unknown layer '{dest_area}/{dest_layer}'"
            elif ranks[dest_layer] > ranks[layer]:
                yield f"{where}: '{dest_layer}' is above '{layer}' in the layer order"
            elif ranks[dest_layer] == ranks[layer] and dest_layer != layer:
                yield f"{where}: '{dest_layer}' sits beside '{layer}' in the layer order, not below it"


def main(argv):
    if len(argv) > 2:
        print(__doc__, file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1] if len(argv) == 2 else pathlib.Path(__file__).resolve().parent.parent)
    files = [p for area in ("core", "app") for p in sorted((root / area).rglob("*")) if p.suffix in (".h", ".cpp")]
    if not files:
        print(f"check_layers: no sources under {root}", file=sys.stderr)
        return 2
    problems = [msg for f in files for msg in check_file(root, f)]
    for msg in problems:
        print(msg)
    print(f"check_layers: {len(files)} files, {len(problems)} violations")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
