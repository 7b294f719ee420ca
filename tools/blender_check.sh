#!/usr/bin/env bash
# Exports the default body in each preset and imports every file into Blender headless with
# tools/blender_inspect.py (bone directions, shape keys, heights), then renders the body in a
# fist, an 80-degree arm raise, a 130-degree knee and with a checkerboard on its UVs (the
# blender preset's file, A-pose rest)
# (OUT_DIR/rig/*.png: look at them). Not part of CI: Blender is
# a large optional package (Debian 12: apt-get install blender).
# usage: tools/blender_check.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build} out=${2:-/tmp/sg-blender-check}
if ! command -v blender >/dev/null; then
  echo "blender_check: Blender is not installed (apt-get install blender); nothing to do"
  exit 0
fi
mkdir -p "$out"
betas="0.8 -1.2 0.5 1.5"
"$build/sequential-gallery" measure --betas $betas | grep '^height'
for preset in blender unity threejs vrm; do
  ext=glb
  [ "$preset" = vrm ] && ext=vrm
  "$build/sequential-gallery" export --betas $betas --preset $preset -o "$out/$preset.$ext" >/dev/null
  echo "== preset $preset"
  blender -b --factory-startup --python-exit-code 1 -P tools/blender_inspect.py -- \
    "$out/$preset.$ext" 2>&1 | grep -v "^Blender quit\|^Read prefs\|^Info:\|^$" || exit 1
done
echo "== preset blender, Bone Dir = Blender (each joint's local +Y)"
blender -b --factory-startup --python-exit-code 1 -P tools/blender_inspect.py -- \
  "$out/blender.glb" --bone-dir BLENDER 2>&1 | grep -E "^file|worst|^height" || exit 1
# From the blender preset's A-pose rest, as a rigger posing the .glb would.
echo "== rig check (blender preset): a fist, an 80-degree arm raise, a 130-degree knee, a checkerboard"
mkdir -p "$out/rig"
blender -b --factory-startup --python-exit-code 1 -P tools/blender_inspect.py -- \
  "$out/blender.glb" --rig-check "$out/rig" 2>&1 | grep -E "^file|^armature|finger bones|^rendered|^no " || exit 1
