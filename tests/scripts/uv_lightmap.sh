#!/usr/bin/env bash
# The lightmap workflow from the command line (DESIGN.md §1 uv layout, §5):
# a JSON scene of two UV-mapped meshes (spot.obj and a quad) baked on
# uv:64x64, then numpy/zarr read the store and its chart rectangles, and the
# relit lightmap is written as PNG, EXR, .glb and .gltf (checked by
# uv_lightmap_check.py, which parses the glTF with nothing but json + struct
# + numpy) and as a rotation sequence; a mesh without UVs is refused by name.
set -euo pipefail
WB=$1
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cp "$WB_SHARED_DATA/models/spot.obj" "$TMP/spot.obj"
cat >"$TMP/quad.obj" <<'OBJ'
v -1 -1 -1
v 1 -1 -1
v 1 -1 1
v -1 -1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 4/4 3/3
f 1/1 3/3 2/2
OBJ
cat >"$TMP/scene.json" <<'JSON'
{"meshes": [{"file": "spot.obj"}, {"file": "quad.obj", "albedo": [0.5, 0.6, 0.7]}]}
JSON
"$WB" bake "$TMP/scene.json" --layout uv:64x64 --light-res 8 --workers 2 --quiet \
  --out "$TMP/s.wbk" >"$TMP/bake.txt" 2>&1 || fail "bake: $(cat "$TMP/bake.txt")"

for out in lightmap.png lightmap.exr scene.glb scene.gltf; do
  "$WB" relight "$TMP/s.wbk" --env builtin:constant --terms 384 --out "$TMP/$out" \
    >"$TMP/relight.txt" 2>&1 || fail "relight $out: $(cat "$TMP/relight.txt")"
done
[[ -f "$TMP/scene.bin" ]] || fail ".gltf wrote no .bin beside it"
[[ -z "$(ls -A "$TMP" | grep '^\.')" ]] || fail "work files left: $(ls -A "$TMP")"
/usr/bin/python3 "$HERE/uv_lightmap_check.py" "$TMP" || fail "uv_lightmap_check.py"

"$WB" relight "$TMP/s.wbk" --env builtin:sky --terms 64 --rotate-sequence 0:90:2 \
  --out "$TMP/frames" >"$TMP/seq.txt" 2>&1 || fail "rotate-sequence: $(cat "$TMP/seq.txt")"
[[ $(ls "$TMP/frames" | grep -c '\.png$') == 2 ]] || fail "frames: $(ls "$TMP/frames")"

# A mesh without UVs: refused by name, hilbert suggested, nothing written.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$TMP/bare.obj"
if "$WB" bake "$TMP/bare.obj" --layout uv:16x16 --light-res 8 --quiet --out "$TMP/bare.wbk" \
  >"$TMP/bare.txt" 2>&1; then fail "a mesh without UVs was baked"; fi
grep -q "mesh 'bare' has no UV channel 0" "$TMP/bare.txt" || fail "message: $(cat "$TMP/bare.txt")"
grep -q "hilbert" "$TMP/bare.txt" || fail "no hilbert suggestion: $(cat "$TMP/bare.txt")"
[[ ! -e "$TMP/bare.wbk" ]] || fail "a refused bake left its output"
echo "uv_lightmap: ok"
