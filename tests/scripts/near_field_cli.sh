#!/usr/bin/env bash
# The near-field commands from the shell: a plane:S bake that python zarr
# reads (M = N², light_domain in .zattrs), `relight --area-light` with the
# repository's example light (and a sequence), `eval --reference
# --area-light --json` close to the reference and far from the distant
# treatment, and the errors that name what is wrong.
set -euo pipefail
WB=$1
SRC=${WB_SOURCE_DIR:?}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
"$WB" bake builtin:furnace --layout camera:16x16 --light-res 16 --light-domain plane:4 --quiet \
  --out "$TMP/plane.wbk" >/dev/null
"$WB" bake builtin:furnace --layout camera:16x16 --light-res 8 --quiet --out "$TMP/cube.wbk" >/dev/null
/usr/bin/python3 - "$TMP/plane.wbk" <<'PY' || fail "the plane store is not what python zarr expects"
import sys, zarr
g = zarr.open(sys.argv[1], mode="r")
assert g.attrs["params"]["light_domain"] == "plane:4", g.attrs["params"]
assert g.attrs["M"] == 256 and g["transport/indptr"].shape == (257,)
PY
cd "$SRC"  # the light file is a path from the project root
"$WB" relight "$TMP/plane.wbk" --area-light docs/lights/softbox.json --out "$TMP/near.png" >/dev/null
[ -s "$TMP/near.png" ] || fail "relight --area-light wrote no image"
cat > "$TMP/seq.json" <<'J'
{"frames": 2, "from": {"centre": [0, 0], "height": 1, "size": [0.5, 0.5]}, "to": {"height": 2}}
J
"$WB" relight "$TMP/plane.wbk" --area-light-sequence "$TMP/seq.json" --out "$TMP/frames" >/dev/null
[ -s "$TMP/frames/frame_0001.png" ] && [ -s "$TMP/frames/timing.csv" ] || fail "no sequence frames"
"$WB" eval "$TMP/plane.wbk" --reference --area-light docs/lights/softbox.json --json \
  --reference-batches 4 >"$TMP/eval.json"
/usr/bin/python3 - "$TMP/eval.json" <<'PY' || fail "eval --area-light: $(cat "$TMP/eval.json")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["near_field"]["rel_rms"] < 0.05, j["near_field"]
assert j["distant"]["rel_rms"] > 3 * j["near_field"]["rel_rms"], j["distant"]
assert [g["face_size"] for g in j["grazing_loss"]][:2] == [2, 3]
PY
expect_error() {  # expect_error CODE PATTERN cmd...: that exit code and message
  local code=$1 pattern=$2; shift 2
  set +e; out=$("$@" 2>&1); rc=$?; set -e
  [ "$rc" = "$code" ] || fail "'$*' exited $rc (expected $code): $out"
  grep -q -- "$pattern" <<<"$out" || fail "'$*' said '$out' (expected '$pattern')"
}
expect_error 1 "light-domain plane:S" "$WB" relight "$TMP/cube.wbk" --area-light docs/lights/softbox.json --out "$TMP/x.png"
expect_error 1 "relight it with --area-light" "$WB" relight "$TMP/plane.wbk" --env builtin:sky --out "$TMP/x.png"
echo '{"centre": [0, 0], "height": 1, "size": [1, 1], "colour": [1, 1, 1]}' >"$TMP/bad.json"
expect_error 2 "colour: unknown key" "$WB" relight "$TMP/plane.wbk" --area-light "$TMP/bad.json" --out "$TMP/x.png"
expect_error 2 "light_domain: plane size 11" "$WB" bake builtin:furnace --light-domain plane:11 --out "$TMP/y.wbk"
[ ! -e "$TMP/x.png" ] && [ ! -e "$TMP/y.wbk" ] || fail "a refused command left an output"
echo "PASS: plane bake, relight and eval with area lights, and their errors"
