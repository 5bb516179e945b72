#!/usr/bin/env bash
# A damaged store is DATA_LOSS naming the damaged chunk, for `relight`, `eval`
# and `fetch`'s verification — never a silently wrong result. A deleted chunk
# used to read as zeros (Zarr's fill value): relight wrote an almost black
# image and eval reported rel_rms 0.99997, both with rc 0.
source "$(dirname "$0")/cluster_lib.bash" "$1"

start_coordinator "$TMP/data" "$(free_port)"
start_worker w1 "$TMP/data/store" --threads 2
job=$("$WB" submit builtin:cubes-wall --layout camera:32x32 --light-res 8 --output-name c.wbk \
  --coordinator "$ADDR")
wait_until 60 "job $job DONE" job_phase_is "$job" DONE
"$WB" fetch "$job" --out "$TMP/good.wbk" --coordinator "$ADDR" >/dev/null

# expect_loss WHAT COMMAND...: non-zero, DATA_LOSS, naming WHAT.
expect_loss() {
  local what=$1
  shift
  if timeout 60 "$@" >"$TMP/out.txt" 2>"$TMP/err.txt"; then fail "accepted a damaged store: $*"; fi
  grep -qF "DATA_LOSS" "$TMP/err.txt" || fail "not DATA_LOSS: $* -- $(cat "$TMP/err.txt")"
  grep -qF -- "$what" "$TMP/err.txt" || fail "does not name $what: $(cat "$TMP/err.txt")"
}

for chunk in transport/data/0 transport/indices/0 transport/scale/0 samples/position/0.0; do
  rm -rf "$TMP/bad.wbk"
  cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
  rm "$TMP/bad.wbk/$chunk"
  expect_loss "bad.wbk/$chunk" "$WB" relight "$TMP/bad.wbk" --env builtin:sky --out "$TMP/o.png"
  [[ ! -e $TMP/o.png ]] || fail "relight of a damaged store wrote an image"
done
expect_loss "bad.wbk/samples/position/0.0" "$WB" eval "$TMP/bad.wbk" --env builtin:sky --reference \
  --no-dense
# What held: a flipped byte and a truncated chunk are caught by the zstd checksums.
rm -rf "$TMP/bad.wbk" && cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
printf '\xff' | dd of="$TMP/bad.wbk/transport/data/0" bs=1 seek=20 conv=notrunc status=none
expect_loss "bad.wbk/transport/data/0" "$WB" relight "$TMP/bad.wbk" --env builtin:sky --out "$TMP/o.png"
rm -rf "$TMP/bad.wbk" && cp -r "$TMP/good.wbk" "$TMP/bad.wbk"
truncate -s 10 "$TMP/bad.wbk/transport/indptr/0"
expect_loss "bad.wbk/transport/indptr/0" "$WB" relight "$TMP/bad.wbk" --env builtin:sky \
  --out "$TMP/o.png"

# fetch: a chunk gone from the coordinator's copy fails the verification, and
# nothing is left at --out or beside it.
rm "$TMP/data/store/c.wbk/transport/data/0"
expect_loss "transport/data/0" "$WB" fetch "$job" --out "$TMP/f.wbk" --coordinator "$ADDR"
[[ -z $(find "$TMP" -maxdepth 1 -name '*f.wbk*') ]] || fail "fetch left $(ls -A "$TMP")"
echo "PASS: missing, flipped and truncated chunks are DATA_LOSS naming the chunk"
