#!/usr/bin/env bash
# Every numeric result is finite or an error, through the command line:
# a store edited through zarr to hold NaN or inf, a FIFO inside a store,
# area lights and eye positions whose numbers overflow float, and a GGX lobe
# narrower than the store's texels. Each used to exit 0 (NaN or black
# images, `eval` printing rel_rms nan and psnr inf) or hang; each is now a
# non-zero exit naming the input, within a time limit, with no output left.
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$WB" bake builtin:cubes-wall --layout camera:16x16 --light-res 8 --workers 2 --quiet \
  --out "$TMP/good.wbk" >/dev/null || fail "bake"
"$WB" relight "$TMP/good.wbk" --env builtin:sky --out "$TMP/good.png" >/dev/null || fail "relight"

# must_fail WHAT NEEDLE CMD...: non-zero (not a timeout), names NEEDLE, no output left.
must_fail() {
  local what=$1 needle=$2 rc=0
  shift 2
  rm -f "$TMP/o.png" "$TMP/o.exr"
  timeout 60 "$@" >"$TMP/err.txt" 2>&1 || rc=$?
  [[ $rc -ne 0 ]] || fail "$what: exited 0"
  [[ $rc -ne 124 ]] || fail "$what: hung (killed after 60 s)"
  grep -qF -- "$needle" "$TMP/err.txt" || fail "$what: message lacks '$needle': $(cat "$TMP/err.txt")"
  [[ ! -e $TMP/o.png && ! -e $TMP/o.exr ]] || fail "$what: left an image"
}

# A column's quantization step set to NaN, inf and an overflowing 3e38 with
# zarr (valid zstd chunks): DATA_LOSS naming transport/scale[column].
for value in nan inf 3e38; do
  rm -rf "$TMP/bad.wbk" && cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
  column=$(/usr/bin/python3 - "$TMP/bad.wbk" "$value" <<'PY'
import sys, zarr
scale = zarr.open_array(sys.argv[1] + "/transport/scale", mode="r+")
column = int((scale[:] > 0).argmax())
scale[column] = float(sys.argv[2])
print(column)
PY
)
  must_fail "relight, scale $value" "transport/scale[$column]" \
    "$WB" relight "$TMP/bad.wbk" --env builtin:sky --out "$TMP/o.png"
  grep -qF DATA_LOSS "$TMP/err.txt" || fail "scale $value: not DATA_LOSS: $(cat "$TMP/err.txt")"
  must_fail "eval, scale $value" "transport/scale[$column]" \
    "$WB" eval "$TMP/bad.wbk" --env builtin:sky --reference --no-dense
done
# Exposures whose factor 2^stops is no float, and a rotation that is no
# number: each used to exit 0 (a black PNG; eval of the unrotated map).
for stops in nan inf -inf 200; do
  must_fail "exposure $stops" "exposure: " \
    "$WB" relight "$TMP/good.wbk" --env builtin:sky --exposure "$stops" --out "$TMP/o.png"
done
must_fail "exposure 200, a sequence" "exposure: " \
  "$WB" relight "$TMP/good.wbk" --env builtin:sky --exposure 200 --rotate-sequence 0:90:2 --out "$TMP/seq"
[[ ! -e $TMP/seq ]] || fail "exposure 200, a sequence: left $TMP/seq"
for angle in nan inf; do
  must_fail "eval rotate $angle" "rotate: " \
    "$WB" eval "$TMP/good.wbk" --env builtin:sky --rotate "$angle" --no-dense
done
# A NaN normal.
rm -rf "$TMP/bad.wbk" && cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
/usr/bin/python3 - "$TMP/bad.wbk" <<'PY'
import sys, zarr
normal = zarr.open_array(sys.argv[1] + "/samples/normal", mode="r+")
normal[3, 1] = float("nan")
PY
must_fail "relight, NaN normal" "samples/normal[3, 1]" \
  "$WB" relight "$TMP/bad.wbk" --env builtin:sky --out "$TMP/o.png"

# A FIFO as a chunk and as .zattrs: refused at once, not a hang.
for name in transport/data/0 .zattrs transport/indptr/.zarray; do
  rm -rf "$TMP/bad.wbk" && cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
  rm "$TMP/bad.wbk/$name" && mkfifo "$TMP/bad.wbk/$name"
  must_fail "FIFO $name" "not a regular file (a FIFO)" \
    "$WB" relight "$TMP/bad.wbk" --env builtin:sky --out "$TMP/o.png"
done

# Area lights with numbers beyond float's reach.
"$WB" bake builtin:cubes-wall --layout camera:16x16 --light-res 8 --light-domain plane:4 \
  --workers 2 --quiet --out "$TMP/plane.wbk" >/dev/null || fail "plane bake"
light() { echo "{\"centre\": [0, 0], \"height\": 1.5, \"size\": [1, 1], $1}" >"$TMP/l.json"; }
light '"radiance": [3, 3, 3]'
"$WB" relight "$TMP/plane.wbk" --area-light "$TMP/l.json" --out "$TMP/ok.png" >/dev/null ||
  fail "a plain area light"
for case in '"radiance": [1e39, 5, 5]|radiance[0]' '"radiance": [3e38, 5, 5]|radiance[0]' \
  '"rotation_degrees": 1e308|rotation_degrees' '"size": [1e308, 1e308], "radiance": [1, 1, 1]|size[0]'; do
  light "${case%|*}"
  [[ ${case%|*} == *size* ]] &&
    echo '{"centre": [0, 0], "height": 1.5, "size": [1e308, 1e308]}' >"$TMP/l.json"
  must_fail "area light ${case%|*}" "${case#*|}" \
    "$WB" relight "$TMP/plane.wbk" --area-light "$TMP/l.json" --out "$TMP/o.png"
  must_fail "eval area light ${case%|*}" "${case#*|}" \
    "$WB" eval "$TMP/plane.wbk" --reference --area-light "$TMP/l.json"
done

# Eye positions: 1e308 is no float; 3e19 away is far but fine (not black).
"$WB" bake builtin:sphere-plane --layout hilbert:128x64 --light-res 8 --transport visibility \
  --workers 2 --quiet --out "$TMP/mesh.wbk" >/dev/null || fail "mesh bake"
must_fail "view 1e308" "view" \
  "$WB" relight "$TMP/mesh.wbk" --env builtin:sky --brdf phong:16 --view 1e308,0,0 --out "$TMP/o.exr"
"$WB" relight "$TMP/mesh.wbk" --env builtin:sky --brdf phong:16 --view 0,2e18,3e19 \
  --out "$TMP/far.ply" >/dev/null || fail "a far eye"
/usr/bin/python3 - "$TMP/far.ply" <<'PY' || fail "a far eye relit black"
import re, struct, sys
data = open(sys.argv[1], "rb").read()
head, body = data.split(b"end_header\n", 1)
vertices = int(re.search(rb"element vertex (\d+)", head).group(1))
assert b"binary_little_endian" in head and b"property uchar red" in head, head
# x, y, z float32 then red, green, blue uchar per vertex.
colours = [body[15 * v + 12:15 * v + 15] for v in range(vertices)]
lit = sum(1 for c in colours if any(c))
assert lit > vertices // 4, f"{lit} of {vertices} vertices have a colour: the image is black"
PY

# GGX narrower than a texel of the N = 8 cubemap: refused, naming the bound.
"$WB" bake builtin:sphere-plane --layout camera:16x16 --light-res 8 --transport visibility \
  --workers 2 --quiet --out "$TMP/vis.wbk" >/dev/null || fail "visibility bake"
for ggx in ggx:1e-8 ggx:0.01; do
  must_fail "$ggx at N = 8" "narrower than a texel" \
    "$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf "$ggx" --out "$TMP/o.png"
done
"$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf ggx:0.2 --out "$TMP/ggx.png" >/dev/null ||
  fail "ggx:0.2 at N = 8"
echo "PASS: NaN/inf stores, FIFOs, overflowing lights and eyes, unresolvable GGX: refused by name"
