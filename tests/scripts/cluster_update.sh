#!/usr/bin/env bash
# An update over gRPC (DESIGN.md §4 BakeRequest.update_job): `submit NEW
# --update JOB_OR_STORE` names the old store by its job (id or output name),
# never by a path; the coordinator resolves it and the workers load the old
# job's scene from its upload. --update-exact gives the bytes of an embedded
# full bake of the new scene, with a bounce too (the workers gather over the
# new scene); --update by output name reuses rows too, and with a bounce
# gives the bytes of the same update run embedded (its old depths read from
# the old store the coordinator resolved); a bad
# reference, a store without staged rows and a changed parameter are refused
# at submit naming why, and a raw client's update_from or update_scene is
# refused naming the field.
source "$(dirname "$0")/cluster_lib.bash" "$1"
src=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}

mkdir -p "$TMP/client"
cd "$TMP/client"
# a 9×9 grid of the square [-1, 1]² at y = 0, facing +y, and a unit cube
awk 'BEGIN { for (j = 0; j < 9; j++) for (i = 0; i < 9; i++) printf "v %g 0 %g\n", i / 4 - 1, j / 4 - 1
  for (j = 0; j < 8; j++) for (i = 0; i < 8; i++) { a = j * 9 + i + 1
    printf "f %d %d %d\nf %d %d %d\n", a, a + 9, a + 1, a + 1, a + 9, a + 10 } }' >ground.obj
printf 'v %s %s %s\n' -0.5 -0.5 -0.5 0.5 -0.5 -0.5 -0.5 0.5 -0.5 0.5 0.5 -0.5 -0.5 -0.5 0.5 0.5 -0.5 0.5 -0.5 0.5 0.5 0.5 0.5 0.5 >cube.obj
printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n' >>cube.obj
scene() {  # scene X Z: the ground, a block behind (it fixes the bounding box) and a small box at (X, Z)
  cat <<JSON
{"meshes": [{"file": "ground.obj"},
            {"file": "cube.obj", "transform": {"scale": [1.6, 0.8, 0.2], "translate": [0, 0.4, -0.85]}},
            {"file": "cube.obj", "transform": {"scale": 0.15, "translate": [$1, 0.075, $2]}}],
 "camera": {"eye": [0, 1.6, 2.2], "target": [0, 0.1, 0]}}
JSON
}
scene -0.5 0.3 >old.json
scene 0.45 0.35 >new.json
BAKE=(--layout camera:16x16 --light-res 8 --tile-size 8 --column-group 128)
"$WB" bake new.json "${BAKE[@]}" --out "$TMP/full.wbk" --quiet >"$TMP/full.log" 2>&1 ||
  fail "embedded bake of the new scene: $(tail -n 2 "$TMP/full.log")"
BOUNCED=("${BAKE[@]}" --bounces 1 --gather-rays 16)
"$WB" bake new.json "${BOUNCED[@]}" --out "$TMP/full_b.wbk" --quiet >"$TMP/full_b.log" 2>&1 ||
  fail "embedded bake of the new scene with a bounce: $(tail -n 2 "$TMP/full_b.log")"
"$WB" bake old.json "${BOUNCED[@]}" --keep-staging --out "$TMP/old_b.wbk" --quiet \
  >"$TMP/old_b.log" 2>&1 || fail "embedded bake of the old scene with a bounce"
"$WB" bake new.json "${BOUNCED[@]}" --update "$TMP/old_b.wbk" --out "$TMP/local_b.wbk" --quiet \
  >"$TMP/local_b.log" 2>&1 || fail "embedded update with a bounce: $(tail -n 2 "$TMP/local_b.log")"

start_coordinator "$TMP/data" "$(free_port)"
start_worker w1 "$TMP/data/store" --threads 2 --scene-cache "$TMP/worker-cache"
C=(--coordinator "$ADDR")
submit() { "$WB" submit "$@" "${C[@]}" --wait 2>>"$TMP/submit.log"; }
old=$(submit old.json "${BAKE[@]}" --keep-staging --output-name old.wbk) || fail "the old bake"
exact=$(submit new.json "${BAKE[@]}" --update "$old" --update-exact --output-name exact.wbk) ||
  fail "the exact update by job id"
local_=$(submit new.json "${BAKE[@]}" --update old.wbk --output-name local.wbk) ||
  fail "the update by output name"
submit old.json "${BOUNCED[@]}" --keep-staging --output-name old_b.wbk >/dev/null ||
  fail "the old bake with a bounce"
submit new.json "${BOUNCED[@]}" --update old_b.wbk --update-exact --output-name exact_b.wbk \
  >/dev/null || fail "the exact update with a bounce"
submit new.json "${BOUNCED[@]}" --update old_b.wbk --output-name local_b.wbk >/dev/null ||
  fail "the update with a bounce"
cd "$TMP"  # from here on no file of the client's is read

S=$TMP/data/store
same_files() {  # same_files FULL UPDATED: every file but .zattrs byte for byte
  (cd "$1" && find . -type f ! -name .zattrs | sort) >full.files
  (cd "$2" && find . -type f ! -name .zattrs | sort) >updated.files
  diff full.files updated.files >/dev/null || fail "$2 holds other files than $1"
  while read -r f; do
    cmp -s "$1/$f" "$2/$f" || fail "$f of $2 differs from $1"
  done <full.files
}
same_files full.wbk "$S/exact.wbk"
same_files full_b.wbk "$S/exact_b.wbk"
same_files local_b.wbk "$S/local_b.wbk"
/usr/bin/python3 - full.wbk "$S/exact.wbk" "$S/local.wbk" full_b.wbk "$S/exact_b.wbk" \
  local_b.wbk "$S/local_b.wbk" <<'PY' ||
import json, sys
full, exact, local, full_b, exact_b, embedded_b, local_b = (
    json.load(open(d + "/.zattrs")) for d in sys.argv[1:])
for attrs, mode, old in ((exact, "exact", "old.wbk"), (local, "local", "old.wbk"),
                         (exact_b, "exact", "old_b.wbk"), (local_b, "local", "old_b.wbk")):
    u = attrs.pop("update")
    assert u["from"] == old, u["from"]  # the store's name, no path of the server
    assert u["mode"] == mode, u
    assert 0 < u["rows_reused"] < u["rows"], u
    assert u["rows_rebaked"] + u["rows_patched"] > 0, u
    assert u["bounces"] == (1 if old == "old_b.wbk" else 0), u
    if old == "old_b.wbk":
        assert u["columns_recomputed"] == u["columns"], u
        if mode == "local":
            assert u["columns_depth_searched"] < u["columns"], u  # old depths were read
embedded_b.pop("update")
assert exact == full, "exact update's .zattrs differs from the full bake's beyond its record"
assert exact_b == full_b, "the exact update with a bounce differs from its full bake's .zattrs"
assert local_b == embedded_b, "the update with a bounce differs from the embedded one's .zattrs"
PY
  fail "the update records"

refused() {  # refused WHAT EXPECTED ARGS...: submit fails and its message holds EXPECTED
  local what=$1 want=$2
  shift 2
  if "$WB" submit "$@" "${C[@]}" >refused.log 2>&1; then fail "$what was accepted"; fi
  grep -qF -- "$want" refused.log || fail "$what: the refusal does not say '$want': $(cat refused.log)"
}
refused "an unknown job" "update_job: \"999\" is neither" builtin:furnace "${BAKE[@]}" --update 999
refused "a store without staged rows" "bake it with --keep-staging" \
  builtin:furnace "${BAKE[@]}" --update exact.wbk
refused "another light resolution" "parameter light_res is 8 there and 16 here" \
  builtin:furnace --layout camera:16x16 --light-res 16 --tile-size 8 --column-group 128 --update "$old"
refused "another bounce count" "parameter bounces is 0 there and 1 here" builtin:furnace "${BAKE[@]}" --bounces 1 --update "$old"

/usr/bin/python3 -m grpc_tools.protoc -I "$src/proto" --python_out="$TMP" \
  --grpc_python_out="$TMP" "$src/proto/wavebake.proto" || fail "protoc for Python"
/usr/bin/python3 - "$TMP" "$ADDR" "$old" "$S" <<'PY' || fail "a raw client named a server path"
import sys
sys.path.insert(0, sys.argv[1])
import grpc
import wavebake_pb2 as pb
import wavebake_pb2_grpc as rpc
jobs = rpc.JobServiceStub(grpc.insecure_channel(sys.argv[2]))
base = dict(scene=pb.SceneSource(builtin="builtin:furnace"), light_res=8, layout="camera:16x16")
cases = [
    (dict(update_from=sys.argv[4] + "/old.wbk"), "update_from: "),
    (dict(update_from="old.wbk"), "update_from: "),
    (dict(update_job=sys.argv[3], update_from="/etc"), "update_from: "),
    (dict(update_job=sys.argv[3], update_scene=pb.SceneSource(builtin="builtin:furnace")),
     "update_scene: "),
]
for fields, field in cases:
    try:
        jobs.Submit(pb.BakeRequest(**base, **fields))
    except grpc.RpcError as e:
        assert e.code() == grpc.StatusCode.INVALID_ARGUMENT, (fields, e.code(), e.details())
        assert e.details().startswith(field), (fields, e.details())
        continue
    raise SystemExit("accepted %s" % fields)
PY
echo "PASS: submit --update by job id (exact: a full bake's bytes, with a bounce too) and by output name (with a bounce: the embedded update's bytes); bad references, a store without staging, a changed parameter and raw paths refused"
