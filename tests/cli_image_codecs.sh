#!/usr/bin/env bash
# OpenImageIO is opened only when a render meets an image: a plain EXR render loads none of its
# libraries, a PNG preview loads the module beside the binary, and the preview is a real PNG.
# Usage: cli_image_codecs.sh PRISM SOURCE_DIR WORK_DIR
set -u
prism=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
scene=$src/scenes/cornell-box/cornell-box.gltf

# LD_DEBUG=libs reports every shared library the dynamic loader opens, dlopen included.
LD_DEBUG=libs "$prism" render "$scene" --spp 1 --res 8x8 -o plain.exr -q 2>libs-plain.txt || fail "plain render failed"
grep -q "libOpenImageIO" libs-plain.txt && fail "a render without images loaded OpenImageIO"
grep -q "libprism_image_codecs" libs-plain.txt && fail "a render without images opened the image codecs module"

LD_DEBUG=libs "$prism" render "$scene" --spp 1 --res 8x8 -o preview.exr --preview preview.png -q 2>libs-png.txt ||
  fail "render with a preview failed"
grep -q "$(dirname "$prism")/libprism_image_codecs.so" libs-png.txt || fail "the preview did not open the module beside prism"
[ "$(head -c 8 preview.png | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "preview.png is not a PNG"
echo "plain render: no OpenImageIO; preview: $(dirname "$prism")/libprism_image_codecs.so opened, PNG written"
