#!/usr/bin/env bash
# DESIGN.md §4, §5 errors through the CLI: a wrong or missing bearer token is
# UNAUTHENTICATED, malformed requests and bad scenes are INVALID_ARGUMENT
# naming the field, an unknown job is NOT_FOUND — each with a non-zero exit
# status. The embedded bake leaves nothing at OUT when it fails.
source "$(dirname "$0")/cluster_lib.bash" "$1"

echo "s3cret-token" >"$TMP/token"
echo "wrong-token" >"$TMP/wrong"
start_coordinator "$TMP/data" "$(free_port)" --token-file "$TMP/token" --max-upload-mb 1

# expect_error STATUS_TEXT COMMAND...: exits non-zero and says STATUS_TEXT.
expect_error() {
  local want=$1
  shift
  if "$@" >"$TMP/out.txt" 2>"$TMP/err.txt"; then fail "succeeded, expected $want: $*"; fi
  grep -qF -- "$want" "$TMP/err.txt" || fail "expected '$want' from: $* -- got: $(cat "$TMP/err.txt")"
}
AUTH=(--coordinator "$ADDR" --token-file "$TMP/token")

expect_error UNAUTHENTICATED "$WB" status --coordinator "$ADDR"
expect_error UNAUTHENTICATED "$WB" status --coordinator "$ADDR" --token-file "$TMP/wrong"
expect_error UNAUTHENTICATED "$WB" submit builtin:furnace --coordinator "$ADDR"
expect_error UNAUTHENTICATED "$WB" worker --store-root "$TMP/data/store" --coordinator "$ADDR" \
  --token-file "$TMP/wrong"
expect_error "token_file" "$WB" status --coordinator "$ADDR" --token-file "$TMP/missing"

expect_error "NOT_FOUND" "$WB" status 4242 "${AUTH[@]}"
expect_error "NOT_FOUND" "$WB" cancel 4242 "${AUTH[@]}"
expect_error "NOT_FOUND" "$WB" watch 4242 "${AUTH[@]}"
expect_error "NOT_FOUND" "$WB" fetch 4242 --out "$TMP/x.wbk" "${AUTH[@]}"
expect_error "INVALID_ARGUMENT: id:" "$WB" status not-a-job "${AUTH[@]}"

# Refused by the coordinator, field first.
expect_error "INVALID_ARGUMENT: scene.builtin:" "$WB" submit builtin:no-such-scene "${AUTH[@]}"
expect_error "INVALID_ARGUMENT: output_name:" "$WB" submit builtin:furnace --output-name .hidden \
  "${AUTH[@]}"
printf 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n' >"$TMP/nan.obj"
expect_error "INVALID_ARGUMENT: scene.uploaded:" "$WB" submit "$TMP/nan.obj" "${AUTH[@]}"
printf '# no geometry\n' >"$TMP/empty.obj"
expect_error "INVALID_ARGUMENT: scene.uploaded:" "$WB" submit "$TMP/empty.obj" "${AUTH[@]}"
# An uploaded JSON scene reaches no server file: absolute paths and ".." are
# refused naming the field (by the client before it uploads; the coordinator's
# own refusal of a raw client is cluster_json_scene's), and no answer names a
# path of the coordinator beyond the reference itself.
cp "$WB_SHARED_DATA/models/bunny.obj" "$TMP/data/server.obj"
for ref in "$TMP/data/server.obj" "../../server.obj" "../../../../../../etc/passwd"; do
  printf '{"meshes": [{"file": "%s"}]}\n' "$ref" >"$TMP/evil.json"
  expect_error "INVALID_ARGUMENT:" "$WB" submit "$TMP/evil.json" --layout hilbert:64x64 "${AUTH[@]}"
  grep -qF "meshes[0].file: '$ref'" "$TMP/err.txt" || fail "no field named: $(cat "$TMP/err.txt")"
  if sed "s|$ref||g" "$TMP/err.txt" | grep -qF "$TMP/data"; then
    fail "a server path reached the client: $(cat "$TMP/err.txt")"
  fi
done
# A layout that does not fit the scene is refused at submit, before any task.
expect_error "INVALID_ARGUMENT: layout: camera:32x32 needs the scene's camera" \
  "$WB" submit "$WB_SHARED_DATA/models/bunny.obj" --layout camera:32x32 "${AUTH[@]}"
expect_error "INVALID_ARGUMENT: layout: hilbert:32x32: scene 'bunny' has 2503 vertices" \
  "$WB" submit "$WB_SHARED_DATA/models/bunny.obj" --layout hilbert:32x32 "${AUTH[@]}"
[[ -z $("$WB" status "${AUTH[@]}" | grep -v '^ *$' | tail -n +2) ]] ||
  fail "refused submits made jobs: $("$WB" status "${AUTH[@]}")"
head -c 1500000 /dev/zero | tr '\0' '#' | fold -w 100 >"$TMP/big.obj" # past the upload limit
expect_error "INVALID_ARGUMENT: data:" "$WB" submit "$TMP/big.obj" "${AUTH[@]}"
# Refused before sending.
expect_error "light_res:" "$WB" submit builtin:furnace --light-res 33 "${AUTH[@]}"
expect_error "SCENE:" "$WB" submit "$TMP/no-such-file.obj" "${AUTH[@]}"
expect_error "SCENE:" "$WB" submit "$TMP" "${AUTH[@]}" # a directory
"$WB" status "${AUTH[@]}" >/dev/null || fail "the right token was refused"

# Nothing of a job was left by any of the refusals (the store root's own
# marker and lock are the coordinator's, there from its start).
left=$(ls -A "$TMP/data/store" | grep -vxF -e .wavebake-store-root -e .wavebake-coordinator.lock || true)
[[ -z $left ]] || fail "refused jobs left files: $left"

# The embedded bake: bad input fails before or during the bake, leaving nothing.
cd "$TMP"
expect_error "light_res:" "$WB" bake builtin:furnace --light-res 12 --out out.wbk
expect_error "scene.uploaded:" "$WB" bake "$TMP/nan.obj" --light-res 8 --out out.wbk
expect_error "scene.builtin:" "$WB" bake builtin:nope --out out.wbk
[[ -z $(find "$TMP" -maxdepth 1 -name 'out.wbk*' -o -maxdepth 1 -name '.out.wbk*') ]] ||
  fail "a failed bake left $(ls -A "$TMP")"
echo "PASS: UNAUTHENTICATED, INVALID_ARGUMENT and NOT_FOUND through the CLI"
