#!/usr/bin/env bash
# Glossy relighting end to end through the command line (issue 13):
# `bake --transport visibility` records the transport in .zattrs (a diffuse
# store does not: it stays as before); `relight --brdf` writes images and
# vertex colours and refuses what it cannot do by name (a glossy BRDF on a
# diffuse store, --view on a camera layout, no --view on a mesh layout, a bad
# BRDF); `--brdf-sequence` held static converges to every BRDF term
# (basic incremental) and keeps its budget's error without it; `eval
# --reference --brdf` measures against the glossy reference.
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

bake() {  # NAME SCENE LAYOUT TRANSPORT
  "$WB" bake "$2" --layout "$3" --light-res 8 --transport "$4" --workers 2 --quiet \
    --out "$TMP/$1.wbk" >/dev/null || fail "bake $1"
}
bake vis builtin:sphere-plane camera:16x16 visibility
bake dif builtin:sphere-plane camera:16x16 diffuse
bake mesh builtin:sphere-plane hilbert:128x64 visibility

/usr/bin/python3 - "$TMP" <<'PY' || fail ".zattrs transport"
import json, sys
vis = json.load(open(sys.argv[1] + "/vis.wbk/.zattrs"))
dif = json.load(open(sys.argv[1] + "/dif.wbk/.zattrs"))
assert vis["transport"] == "visibility" and vis["params"]["transport"] == "visibility", vis
assert "transport" not in dif and "transport" not in dif["params"], dif["params"]
PY

# must_fail WHAT NEEDLE CMD... : non-zero exit, message names the problem, no output left
must_fail() {
  local what=$1 needle=$2
  shift 2
  if "$@" >"$TMP/err.txt" 2>&1; then fail "$what: succeeded"; fi
  grep -q -- "$needle" "$TMP/err.txt" || fail "$what: message lacks '$needle': $(cat "$TMP/err.txt")"
}

"$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf phong:32 --out "$TMP/vis.png" >/dev/null ||
  fail "relight phong"
[[ -s "$TMP/vis.png" ]] || fail "no png"
"$WB" relight "$TMP/dif.wbk" --env builtin:sky --brdf lambert --out "$TMP/dif.png" >/dev/null ||
  fail "a diffuse store relights as lambert"
must_fail "glossy on diffuse" "--transport visibility" \
  "$WB" relight "$TMP/dif.wbk" --env builtin:sky --brdf ggx:0.3 --out "$TMP/x.png"
must_fail "visibility on a plane domain" "light_domain: a visibility transport needs the cube" \
  "$WB" bake builtin:cubes-wall --layout camera:8x8 --light-res 8 --light-domain plane:4 \
  --transport visibility --quiet --out "$TMP/plane.wbk"
[[ ! -e "$TMP/plane.wbk" ]] || fail "a refused bake left $TMP/plane.wbk"
must_fail "view on camera" "view" \
  "$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf phong:32 --view 0,1,3 --out "$TMP/x.png"
must_fail "bad brdf" "brdf" \
  "$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf phong:-2 --out "$TMP/x.png"
must_fail "mesh without view" "--view" \
  "$WB" relight "$TMP/mesh.wbk" --env builtin:sky --brdf blinn:16 --out "$TMP/x.ply"
[[ ! -e "$TMP/x.png" && ! -e "$TMP/x.ply" ]] || fail "a refused relight left output"
"$WB" relight "$TMP/mesh.wbk" --env builtin:sky --brdf blinn:16 --view 0,2,3.2 \
  --out "$TMP/mesh.ply" >/dev/null || fail "relight mesh with view"
[[ -s "$TMP/mesh.ply" ]] || fail "no ply"

# Material editing: 3 frames of change, 6 held; 16 BRDF terms per frame.
"$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf-sequence phong:8:64:3:6 --brdf-terms 16 \
  --out "$TMP/basic" >/dev/null || fail "brdf-sequence basic"
"$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf-sequence phong:8:64:3:6 --brdf-terms 16 \
  --incremental none --out "$TMP/none" >/dev/null || fail "brdf-sequence none"
/usr/bin/python3 - "$TMP" <<'PY' || fail "brdf-sequence errors"
import csv, sys
basic = list(csv.DictReader(open(sys.argv[1] + "/basic/errors.csv")))
none = list(csv.DictReader(open(sys.argv[1] + "/none/errors.csv")))
assert len(basic) == 9 and basic[-1]["brdf"] == "phong:64", basic
assert float(basic[-1]["rel_rms"]) < 1e-5, basic[-1]       # held: converged
assert float(none[-1]["rel_rms"]) > 100 * float(basic[-1]["rel_rms"]) and float(none[-1]["rel_rms"]) > 1e-3, none[-1]
PY
[[ -s "$TMP/basic/frame_0008.png" ]] || fail "no frames"
must_fail "per-band materials" "basic" \
  "$WB" relight "$TMP/vis.wbk" --env builtin:sky --brdf-sequence phong:8:64:3 --incremental per-band \
  --out "$TMP/pb"

"$WB" eval "$TMP/vis.wbk" --env builtin:sky --reference --brdf phong:16 --json >"$TMP/eval.json" ||
  fail "eval --brdf"
/usr/bin/python3 - "$TMP/eval.json" <<'PY' || fail "eval --brdf json"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["reference"]["converged"] and r["reference"]["rel_se"] < 0.01, r
for k in ("dense", "compressed"):
    assert 0 < r[k]["rel_rms"] < 0.5, r
PY
must_fail "eval glossy on diffuse" "--transport visibility" \
  "$WB" eval "$TMP/dif.wbk" --env builtin:sky --reference --brdf phong:16
echo OK
