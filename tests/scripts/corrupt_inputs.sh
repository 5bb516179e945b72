#!/usr/bin/env bash
# Truncated and corrupt environment files end `relight` and `eval` with an
# error naming the file, at once: a truncated Radiance .hdr used to spin at
# 100 % CPU forever (stb_image's RLE loop at the end of the data). Every run
# has a time limit; rc 124 is the hang coming back.
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
GRACE=${WB_SHARED_DATA:?}/probes/grace.hdr

# expect_refused FILE COMMAND...: fails within 20 s, non-zero, naming FILE.
expect_refused() {
  local file=$1 rc=0
  shift
  timeout 20 "$@" >"$TMP/out.txt" 2>"$TMP/err.txt" || rc=$?
  ((rc != 124)) || fail "hung (killed after 20 s): $*"
  ((rc != 0)) || fail "accepted $file: $*"
  grep -qF -- "$file" "$TMP/err.txt" || fail "error does not name $file: $(cat "$TMP/err.txt")"
}

"$WB" bake builtin:cubes-wall --layout camera:64x32 --light-res 8 --quiet --out "$TMP/s.wbk" \
  >/dev/null
# A 64x32 relit image is a 2:1 EXR to damage; whole, it reads (and is then
# refused for its masked NaN pixels, a later check).
"$WB" relight "$TMP/s.wbk" --env builtin:sky --out "$TMP/env.exr" >/dev/null
expect_refused "env.exr" "$WB" relight "$TMP/s.wbk" --env "$TMP/env.exr" --out "$TMP/o.png"
grep -qF "radiance must be finite" "$TMP/err.txt" || fail "the whole EXR: $(cat "$TMP/err.txt")"

size=$(stat -c %s "$GRACE")
for n in 50000 120 119 60 11 $((size - 1)) $((size / 3)); do
  head -c "$n" "$GRACE" >"$TMP/cut$n.hdr"
  expect_refused "cut$n.hdr" "$WB" relight "$TMP/s.wbk" --env "$TMP/cut$n.hdr" --out "$TMP/o.png"
done
expect_refused "cut50000.hdr" "$WB" eval "$TMP/s.wbk" --env "$TMP/cut50000.hdr" --reference --no-dense

exr=$(stat -c %s "$TMP/env.exr")
for n in $((exr - 1)) $((exr / 2)) 400 40 4; do
  head -c "$n" "$TMP/env.exr" >"$TMP/cut$n.exr"
  expect_refused "cut$n.exr" "$WB" relight "$TMP/s.wbk" --env "$TMP/cut$n.exr" --out "$TMP/o.png"
  grep -qF "unreadable EXR" "$TMP/err.txt" || fail "cut at $n: $(cat "$TMP/err.txt")"
done
# Garbage in the middle of the pixel data: an error or an image, never a hang.
for f in "$GRACE" "$TMP/env.exr"; do
  ext=${f##*.}
  cp "$f" "$TMP/noise.$ext"
  head -c 2000 /dev/urandom | dd of="$TMP/noise.$ext" bs=1 seek=$(($(stat -c %s "$f") / 2)) \
    conv=notrunc status=none
  rc=0
  timeout 20 "$WB" relight "$TMP/s.wbk" --env "$TMP/noise.$ext" --out "$TMP/o.png" \
    >/dev/null 2>&1 || rc=$?
  ((rc != 124)) || fail "hung on noise in $f"
done
echo "PASS: truncated and corrupt HDR/EXR environments are refused, naming the file, at once"
