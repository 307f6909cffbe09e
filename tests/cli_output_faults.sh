#!/bin/bash
# Output faults: a missing directory, a directory in the output's place, a read-only directory,
# a file-size limit (ulimit -f) and a full disk (a 64 KiB tmpfs) each give exit code 4 and a
# message naming the output and the reason; no temporary file is left behind and an earlier
# output of the same name is kept intact. Cases that need mount (as root) or a non-root user are
# skipped with a message where neither is available.
# Usage: cli_output_faults.sh PRISM SCENE WORK_DIR
set -u
prism=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
failures=0
mounted=()
cleanup() { for m in "${mounted[@]}"; do umount "$m" 2>/dev/null; done; }
trap cleanup EXIT
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
args=(--res 96x96 --spp 1 --aovs all --pixel-type float --compression none -q)

# Runs prism writing $2 (after the other arguments), expects exit 4 and stderr containing $1 and
# naming the file at fault ($named, else $2), then checks that no temporary file is left in $2's
# directory.
expect_output_error() {
  local fragment=$1 out=$2 name=$3
  shift 3
  "$prism" render "$scene" "${args[@]}" -o "$out" "$@" 2>err.txt
  local code=$?
  [ $code -eq 4 ] || { fail "$name: exit $code, expected 4: $(cat err.txt)"; return; }
  grep -qF -- "$fragment" err.txt || fail "$name: stderr lacks '$fragment': $(cat err.txt)"
  grep -qF -- "${named:-$out}" err.txt || fail "$name: the message does not name ${named:-$out}"
  local dir
  dir=$(dirname "$out")
  [ -d "$dir" ] && ls -a "$dir" | grep -q '\.tmp-' && fail "$name: a temporary file was left in $dir"
  echo "ok   $name: $(head -1 err.txt)"
}

# An earlier output that a failed write must not destroy.
earlier() { echo "earlier render" >"$1"; }
kept() { [ "$(cat "$1")" = "earlier render" ] || fail "$2: the earlier $1 was destroyed"; }

expect_output_error "does not exist" "$work/missing/out.exr" "missing directory"
[ -e "$work/missing" ] && fail "missing directory: it was created"

mkdir -p "$work/is-a-dir.exr"
expect_output_error "output path is a directory" "$work/is-a-dir.exr" "output path is a directory"

named=$work/missing/p.png expect_output_error "does not exist" "$work/ok.exr" "preview in a missing directory" \
  --preview "$work/missing/p.png"
[ -e "$work/ok.exr" ] && fail "preview in a missing directory: the render ran and wrote its EXR before failing"

# A file-size limit of 16 KiB: the EXR (96x96, every AOV, float) is far larger.
earlier "$work/limited.exr"
(failures=0; ulimit -f 16; expect_output_error "limited.exr" "$work/limited.exr" "file-size limit (ulimit -f)"; exit $failures)
failures=$((failures + $?))
kept "$work/limited.exr" "file-size limit"

if [ "$(id -u)" -eq 0 ] && mkdir -p "$work/full" && mount -t tmpfs -o size=64k tmpfs "$work/full" 2>/dev/null; then
  mounted+=("$work/full")
  earlier "$work/full/out.exr"
  expect_output_error "out.exr" "$work/full/out.exr" "disk full (64 KiB tmpfs)"
  kept "$work/full/out.exr" "disk full"
  mkdir -p "$work/ro"
  mount -t tmpfs -o ro,size=64k tmpfs "$work/ro" && mounted+=("$work/ro")
  expect_output_error "not writable" "$work/ro/out.exr" "read-only directory"
elif [ "$(id -u)" -ne 0 ]; then
  mkdir -p "$work/ro" && earlier "$work/ro/out.exr" && chmod 555 "$work/ro"
  expect_output_error "not writable" "$work/ro/out.exr" "read-only directory"
  kept "$work/ro/out.exr" "read-only directory"
  chmod 755 "$work/ro"
  echo "skip disk full: needs root to mount a small tmpfs"
else
  echo "skip disk full and read-only directory: cannot mount a tmpfs here"
fi

echo "$failures failures"
[ $failures -eq 0 ]
