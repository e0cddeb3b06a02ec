#!/usr/bin/env bash
# Renders scenes/hw2/Tests at their own settings and puts each beside the assignment's reference image:
# docs/images/contact-sheet.png (left: Penumbra, right: reference; rows: ao, area, solid angle,
# hemisphere). Run from the repository root after tools/setup.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
t=scenes/hw2/Tests r=scenes/hw2/References
build/penumbra render $t/sphere-ao.xml --spp 256 -o "$out/ao.exr"   # the reference predates the 1024-spp bump
build/penumbra render $t/sphere-area.xml -o "$out/area.exr"
build/penumbra render $t/sphere-solid.xml -o "$out/solid.exr"
build/penumbra render $t/sphere-hemisphere.xml -o "$out/hemisphere.exr"
mkdir -p docs/images
build/penumbra_contact_sheet docs/images/contact-sheet.png 2 \
  "$out/ao.exr" $r/sphere-ao.exr "$out/area.exr" $r/sphere-area.exr \
  "$out/solid.exr" $r/sphere-solid.exr "$out/hemisphere.exr" $r/sphere-hemisphere.exr
rm -rf "$out"
