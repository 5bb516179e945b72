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

# A PLY whose header never ends: assimp read on forever (found by the fuzzer).
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_heade[r\n0\n1\n2\n' \
  >"$TMP/cut.ply"
expect_refused "cut.ply" "$WB" bake "$TMP/cut.ply" --layout hilbert:4x4 --light-res 8 \
  --out "$TMP/p.wbk"
# The same behind a magic assimp still takes for PLY ("ply?").
printf 'ply?\nformat ascii 1.0\nelement vertex 3\nproperty float x\n0\n1\n2\n' >"$TMP/odd.ply"
expect_refused "odd.ply" "$WB" bake "$TMP/odd.ply" --layout hilbert:4x4 --light-res 8 \
  --out "$TMP/p.wbk"

# Radiance that would overflow the float relighting (an 8x8 block of RGBE
# exponent 255, 1.7e38) is refused naming the texel: it used to give rc 0, a
# black image and "rel_rms": null. At the documented limit (1e30) everywhere,
# eval's errors are numbers.
/usr/bin/python3 - "$TMP" <<'PY'
import math, sys
w, h = 64, 32
head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
one = bytes([128, 128, 128, 129])  # 1.0, stored flat
over = b"".join(bytes([255] * 4) if 8 <= x < 16 and 4 <= y < 12 else one
                for y in range(h) for x in range(w))
open(sys.argv[1] + "/over.hdr", "wb").write(head + over)
e = math.floor(math.log2(1e30 / 255)) + 137  # mantissa * 2^(e-136) just below 1e30
m = int(1e30 / 2 ** (e - 136))
open(sys.argv[1] + "/max.hdr", "wb").write(head + bytes([m, m, m, e]) * (w * h))
PY
expect_refused "over.hdr: pixel (8, 4) channel R" "$WB" relight "$TMP/s.wbk" --env "$TMP/over.hdr" \
  --out "$TMP/o.exr"
expect_refused "over.hdr: pixel (8, 4)" "$WB" eval "$TMP/s.wbk" --env "$TMP/over.hdr" --reference \
  --no-dense
timeout 60 "$WB" eval "$TMP/s.wbk" --env "$TMP/max.hdr" --reference --json >"$TMP/max.json"
/usr/bin/python3 - "$TMP/max.json" <<'PY' || fail "eval at the radiance limit: $(cat "$TMP/max.json")"
import json, math, sys
r = json.load(open(sys.argv[1]))
for part in ("compressed", "dense"):
    v = r[part]["rel_rms"]
    assert v is not None and math.isfinite(v) and v < 0.5, (part, v)
PY
echo "PASS: truncated, corrupt and overflowing HDR/EXR environments are refused, naming the file, at once"
