#!/bin/bash
# The broken-file matrix: prism renders each deliberately broken glTF file as a user would and
# must give either a clean error (the expected exit code, a message naming the file and the
# reason, no output file) or a documented, finite render (exit 0, the expected warning, no
# non-finite pixel). Rows under /usr/share/assimp (Debian package assimp-testmodels, which
# scripts/install-deps --tests installs) are skipped when it is absent.
# Usage: cli_broken_files.sh PRISM SOURCE_DIR WORK_DIR
set -u
prism=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
broken=$source/tests/broken
assimp=/usr/share/assimp/models/glTF2
failures=0 tried=0 skipped=0

# FILE | EXIT CODE | a fragment of stderr (the reason, or for exit 0 the warning) | extra options
rows=(
  "$broken/triangle.gltf|0||"
  "$broken/triangle.glb|0||"
  "$broken/absurd-count.gltf|3|needs 12884901888 bytes of bufferView 0, which has 36|"
  "$broken/absurd-count-2-40.gltf|3|declares 1099511627776 elements, more than prism accepts|"
  "$broken/absurd-count-no-view.gltf|7|POSITION (accessor 0) needs about 9.0 GiB, more than the memory limit of 1.0 GiB|--memory-limit 1G"
  "$broken/view-past-buffer.gltf|3|bufferView 0 (offset 0, length 4096) runs past the end of buffer 0 (44 bytes)|"
  "$broken/accessor-past-view.gltf|3|needs 44 bytes of bufferView 0, which has 36|"
  "$broken/image-view-past-buffer.gltf|3|image 0: bufferView 2 (offset 40, length 1048576) runs past the end of buffer 0|"
  "$broken/image-not-decodable.gltf|0|image 0: cannot decode image: Not a PNG file; its textures render magenta|"
  "$broken/image-not-decodable.gltf|3|image 0: cannot decode image: Not a PNG file (--strict)|--strict"
  "$broken/image-missing-file.gltf|0|the file 'no-such-texture.png' is missing or empty; its textures render magenta|"
  "$broken/image-missing-file.gltf|3|the file 'no-such-texture.png' is missing or empty (--strict)|--strict"
  "$broken/position-wrong-component-type.gltf|3|POSITION (accessor 0): component type UNSIGNED_BYTE is not allowed here|"
  "$broken/position-wrong-type.gltf|3|POSITION (accessor 0): has 2 components per element, expected 3|"
  "$broken/index-past-vertices.gltf|3|index 2 at position 2 is not below the vertex count 2|"
  "$broken/mesh-out-of-range.gltf|3|\$.nodes[0].mesh: 7 is out of range (the file has 1 meshes)|"
  "$broken/node-cycle.gltf|3|node 0: node hierarchy has a cycle through this node|"
  "$broken/translation-infinite.gltf|3|not valid JSON: number overflow parsing '1e999'|"
  "$broken/required-extension.gltf|3|\$.extensionsRequired: prism does not support KHR_mesh_quantization|"
  "$broken/points-only.gltf|0|points and lines primitives are not rendered (mode 0)|"
  "$broken/not-json.gltf|3|not valid JSON: parse error at line 1, column 42|"
  "$broken/glb-version-1.glb|3|GLB header: version 1, expected 2|"
  "$broken/glb-json-past-end.glb|3|GLB chunk 0: declares 1048576 bytes of JSON|"
  "$broken/glb-bin-too-short.glb|3|byteLength' = 4096, binary size = 44|"
  "$broken/no-such-file.gltf|3|no such file|"
  "$assimp/IndexOutOfRange/IndexOutOfRange.gltf|3|indices: index 255 at position 0 is not below the vertex count 24|"
  "$assimp/IndexOutOfRange/AllIndicesOutOfRange.gltf|3|indices: index 65535 at position 0 is not below the vertex count 24|"
  "$assimp/MissingBin/BoxTextured.gltf|3|File not found : BoxTextured0.bin|"
  "$assimp/RecursiveNodes/RecursiveNodes.gltf|3|node 0: node hierarchy has a cycle through this node|"
  "$assimp/SchemaFailures/sceneWrongType.gltf|3|\$.scene: expected an index (an integer of 0 or more), got a string|"
  "$assimp/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb|3|POSITION: vertex 0 is not finite|"
  "$assimp/BoxBadNormals-glTF-Binary/BoxBadNormals.glb|0|NORMAL: 4 zero-length normals; the face normal shades there|"
  "$assimp/IncorrectVertexArrays/Cube.gltf|0|index count 35 is not a multiple of 3; the rest is ignored|"
  "$assimp/TestNoRootNode/NoScene.gltf|3|\$.scene: 0 is out of range (the file has 0 scenes)|"
  "$assimp/TestNoRootNode/SceneWithoutNodes.gltf|0|the scene has no triangle meshes|"
  "$assimp/wrongTypes/badArray.gltf|3|\$.meshes[0].primitives: expected an array, got an object|"
  "$assimp/wrongTypes/badExtension.gltf|3|baseColorTexture.extensions.KHR_texture_transform: expected an object, got a string|"
  "$assimp/wrongTypes/badNumber.gltf|3|\$.materials[0].normalTexture: the required property 'index' is missing|"
  "$assimp/wrongTypes/badObject.gltf|3|\$.materials[0].pbrMetallicRoughness: expected an object, got an array|"
  "$assimp/wrongTypes/badString.gltf|3|\$.scenes[0].name: expected a string, got 42|"
  "$assimp/wrongTypes/badUint.gltf|3|baseColorTexture.index: expected an index (an integer of 0 or more), got -1|"
  "$assimp/draco/2CylinderEngine.gltf|3|the geometry is Draco-compressed (KHR_draco_mesh_compression), which prism cannot decode|"
)

for row in "${rows[@]}"; do
  IFS='|' read -r file want fragment extra <<<"$row"
  if [[ $file == $assimp/* && ! -d $assimp ]]; then
    skipped=$((skipped + 1))
    continue
  fi
  tried=$((tried + 1))
  out=$work/out-$tried.exr
  # shellcheck disable=SC2086  # extra holds separate options
  timeout 120 "$prism" render "$file" -o "$out" --res 24x24 --spp 2 --env 0.5 --progress none $extra 2>"$work/err" >/dev/null
  code=$?
  err=$(cat "$work/err")
  problem=""
  if [ $code -ne "$want" ]; then
    problem="exit $code, expected $want"
  elif [ -n "$fragment" ] && ! grep -qF -- "$fragment" "$work/err"; then
    problem="stderr lacks '$fragment'"
  elif [ "$want" -ne 0 ] && ! grep -qF -- "$file" "$work/err"; then
    problem="the message does not name the file"
  elif [ "$want" -ne 0 ] && [ -e "$out" ]; then
    problem="an output was written although the render failed"
  elif [ "$want" -eq 0 ] && ! "$prism" compare "$out" "$out" --threshold 1 -q; then
    problem="the image has non-finite pixels (or cannot be read)"
  fi
  ls "$work" | grep -q '\.tmp' && problem="${problem:+$problem; }a temporary file was left behind"
  if [ -n "$problem" ]; then
    failures=$((failures + 1))
    echo "FAIL ${file#"$source/"} $extra: $problem"
    echo "     stderr: $err"
  else
    echo "ok   exit $code ${file#"$source/"} $extra: $(grep -F -- "${fragment:-@@}" "$work/err" | head -1)"
  fi
done
echo "$tried files tried, $skipped skipped (assimp-testmodels absent), $failures failed"
[ $failures -eq 0 ]
