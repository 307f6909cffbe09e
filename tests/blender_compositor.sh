#!/bin/bash
# Renders the Cornell box with every AOV and opens it in Blender's compositor (blender_compositor.py).
# Exits 77 (skipped) when Blender is not installed. Usage: blender_compositor.sh PRISM SOURCE_DIR WORK_DIR
set -u
prism=$1 source=$2 work=$3
blender=$(command -v blender) || { echo "SKIP: Blender is not installed (Debian package blender)"; exit 77; }
rm -rf "$work" && mkdir -p "$work" || exit 1
"$prism" render "$source/scenes/cornell-box/cornell-box.gltf" --res 64x64 --spp 8 --aovs all -q -o "$work/box.exr" || exit 1
"$blender" -b --factory-startup --python-exit-code 1 --python "$source/tests/blender_compositor.py" -- \
  "$work/box.exr" 64 64 "$work" back_wall ceiling floor left_wall light right_wall short_block tall_block 2>&1 |
  grep -E "^BLENDER|Error|SystemExit|Traceback"
exit "${PIPESTATUS[0]}"
