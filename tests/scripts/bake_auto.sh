#!/usr/bin/env bash
# `wavebake bake --auto --target-error E --env ENV...`: a scene that
# needs little (a disk over a plane under constant light: soft, broad
# occlusion) comes out at the coarsest cubemap, a scene with a sharp sun
# shadow (sphere-plane under builtin:sky) gets a finer one; both stores meet
# E when re-measured by `wavebake eval --reference` (its own reference, at a
# tighter standard error than the search's), .zattrs records the choice,
# nothing but the store is left beside it, and conflicting flags are refused
# by name; a target no N reaches fails and writes nothing. Judged by two
# lightings, the store meets E under each (re-measured by eval), its
# recorded error is the worse one's, and each N was traced once.
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# bake_and_check NAME SCENE LAYOUT ENV E → prints the chosen N
bake_and_check() {
  local name=$1 scene=$2 layout=$3 env=$4 e=$5
  "$WB" bake "$scene" --layout "$layout" --auto --target-error "$e" --env "$env" \
    --workers 2 --quiet --out "$TMP/$name.wbk" >"$TMP/$name.txt" ||
    fail "$name: bake --auto failed: $(cat "$TMP/$name.txt")"
  grep -q "^chosen: N=" "$TMP/$name.txt" || fail "$name: no choice printed"
  local n
  n=$(/usr/bin/python3 - "$TMP/$name.wbk" "$e" <<'PY'
import json, sys
attrs = json.load(open(sys.argv[1] + "/.zattrs"))
auto, e = attrs["auto"], float(sys.argv[2])
chosen = auto["chosen"]
assert auto["target_error"] == e, auto["target_error"]
assert chosen["light_res"] == attrs["N"] == attrs["params"]["light_res"], (chosen, attrs["N"])
assert chosen["column_target"] == attrs["params"]["target_error"], attrs["params"]
assert chosen["meets"] and auto["measured_error"] <= e, auto
assert chosen in auto["candidates"], "the choice is one of the candidates"
assert auto["reference"]["rel_se"] < e / 5, auto["reference"]
print(chosen["light_res"])
PY
  ) || fail "$name: .zattrs auto record"
  local terms=$((6 * n * n))
  "$WB" eval "$TMP/$name.wbk" --env "$env" --reference --reference-se 0.001 --terms "$terms" \
    --no-dense --json >"$TMP/$name.json" || fail "$name: eval"
  /usr/bin/python3 - "$TMP/$name.json" "$e" <<'PY' || fail "$name: eval says the target is missed"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["compressed"]["rel_rms"] <= float(sys.argv[2]), r
PY
  echo "$n"
}

soft=$(bake_and_check soft builtin:disk-over-plane camera:16x16 builtin:constant 0.05)
sharp=$(bake_and_check sharp builtin:sphere-plane camera:16x16 builtin:sky 0.01)
[ "$soft" -eq 8 ] || fail "soft scene chose N=$soft, expected the coarsest, 8"
[ "$sharp" -ge 32 ] || fail "sharp sun shadow chose N=$sharp, expected at least 32"
leftovers=$(ls -A "$TMP" | grep -v -E '^(soft|sharp)\.(wbk|txt|json)$' || true)
[ -z "$leftovers" ] || fail "left beside the output: $leftovers"

# Two lightings: the worst of them counts.
GRACE="$WB_SHARED_DATA/probes/grace.hdr"
"$WB" bake builtin:sphere-plane --layout camera:16x16 --auto --target-error 0.02 \
  --env builtin:sky --env "$GRACE" --workers 2 --quiet --out "$TMP/both.wbk" >"$TMP/both.txt" ||
  fail "two envs: $(cat "$TMP/both.txt")"
/usr/bin/python3 - "$TMP/both.wbk" "$GRACE" <<'PY' || fail "two envs: .zattrs auto record"
import json, sys
auto = json.load(open(sys.argv[1] + "/.zattrs"))["auto"]
assert auto["envs"] == ["builtin:sky", sys.argv[2]], auto["envs"]
chosen = auto["chosen"]
by_env = chosen["e_tot_by_env"]
assert set(by_env) == set(auto["envs"]), by_env
assert chosen["e_tot"] == max(by_env.values()), chosen
assert all(e <= auto["target_error"] for e in by_env.values()), by_env
resolutions = {c["light_res"] for c in auto["candidates"]}
assert auto["traces"]["light_resolutions"] == len(resolutions), (auto["traces"], resolutions)
PY
n=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['N'])" "$TMP/both.wbk/.zattrs")
for env in builtin:sky "$GRACE"; do
  "$WB" eval "$TMP/both.wbk" --env "$env" --reference --reference-se 0.001 --terms $((6 * n * n)) \
    --no-dense --json >"$TMP/both.json" || fail "two envs: eval under $env"
  /usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); assert r['compressed']['rel_rms'] <= 0.02, r" \
    "$TMP/both.json" || fail "two envs: the store misses 0.02 under $env"
done
rm -rf "$TMP/both.wbk" "$TMP/both.txt" "$TMP/both.json"

# A target no N up to --max-light-res reaches: exit 1 naming it, nothing written.
if "$WB" bake builtin:sphere-plane --layout camera:16x16 --auto --target-error 0.01 \
  --max-light-res 16 --env builtin:sky --quiet --out "$TMP/none.wbk" >/dev/null 2>"$TMP/none.err"; then
  fail "an unreachable target was accepted"
fi
grep -q "no light resolution up to 16 meets target error 0.01" "$TMP/none.err" ||
  fail "unreachable target: $(cat "$TMP/none.err")"
leftovers=$(ls -A "$TMP" | grep -v -E '^(soft|sharp)\.(wbk|txt|json)$|^none\.err$' || true)
[ -z "$leftovers" ] || fail "a failed search left: $leftovers"

# Flags: --auto owns N, terms and bits and needs an explicit target.
expect_refused() {
  local flag=$1
  shift
  if "$WB" bake builtin:furnace --out "$TMP/x.wbk" --quiet "$@" 2>"$TMP/err.txt"; then
    fail "accepted: $*"
  fi
  grep -q -- "$flag" "$TMP/err.txt" || fail "error for '$*' does not name $flag: $(cat "$TMP/err.txt")"
}
expect_refused --target-error --auto
expect_refused --light-res --auto --target-error 0.05 --light-res 16
expect_refused --column-terms --auto --target-error 0.05 --column-terms 8
expect_refused --bits --auto --target-error 0.05 --bits 8
expect_refused --column-mode --auto --target-error 0.05 --column-mode 2d
expect_refused --env --env builtin:sky
[ ! -e "$TMP/x.wbk" ] || fail "a refused bake wrote its output"
echo "PASS: --auto chose N=$soft (soft) and N=$sharp (sharp sun), both within target"
