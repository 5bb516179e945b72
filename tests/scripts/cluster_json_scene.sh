#!/usr/bin/env bash
# A JSON scene that references mesh files bakes on a remote cluster
# (DESIGN.md §4 UploadScene): submit uploads the scene and each mesh by its
# content hash, the coordinator and the workers load it from a directory of
# exactly those files, so the client's directory may be gone before the bake
# starts. The store equals an embedded bake of the same scene in every array;
# a scene naming a path outside its directory is refused, naming the field.
source "$(dirname "$0")/cluster_lib.bash" "$1"
DATA=${WB_SHARED_DATA:?WB_SHARED_DATA: the shared data directory}

mkdir -p "$TMP/client/meshes"
cp "$DATA/models/bunny.obj" "$TMP/client/meshes/bunny.obj"
cat >"$TMP/client/pair.json" <<'JSON'
{"meshes": [{"file": "meshes/bunny.obj", "albedo": [0.8, 0.7, 0.6]},
            {"file": "meshes/bunny.obj", "transform": {"translate": [0.3, 0, 0]}}]}
JSON
BAKE=(--layout hilbert:128x128 --light-res 8 --supersample 1)
"$WB" bake "$TMP/client/pair.json" "${BAKE[@]}" --out "$TMP/ref.wbk" >"$TMP/ref.log" 2>&1 ||
  fail "embedded bake of the JSON scene: $(tail -n 2 "$TMP/ref.log")"

start_coordinator "$TMP/data" "$(free_port)"
job=$("$WB" submit "$TMP/client/pair.json" "${BAKE[@]}" --output-name pair.wbk --coordinator "$ADDR") ||
  fail "submit of the JSON scene"
rm -rf "$TMP/client"  # from here on, only the uploaded bytes exist
start_worker w1 "$TMP/data/store" --threads 2 --scene-cache "$TMP/worker-cache"
timeout 120 "$WB" watch "$job" --coordinator "$ADDR" >"$TMP/watch.log" 2>&1 ||
  fail "the bake did not finish: $(tail -n 3 "$TMP/watch.log")"
# The same arrays; the manifests differ only in how the scene was named.
(cd "$TMP/ref.wbk" && find . -type f ! -name .zattrs | sort) >"$TMP/ref.files"
(cd "$TMP/data/store/pair.wbk" && find . -type f ! -name .zattrs | sort) >"$TMP/out.files"
diff "$TMP/ref.files" "$TMP/out.files" >/dev/null || fail "the stores hold different files"
while read -r f; do
  cmp -s "$TMP/ref.wbk/$f" "$TMP/data/store/pair.wbk/$f" || fail "$f differs from the embedded bake"
done <"$TMP/ref.files"
ls "$TMP/worker-cache/bundles" >/dev/null 2>&1 || fail "the worker built no bundle directory"

# Paths that leave the scene's directory are refused at submit, naming the field.
mkdir -p "$TMP/bad"
cp "$DATA/models/bunny.obj" "$TMP/bunny.obj"
for path in ../bunny.obj "$TMP/bunny.obj"; do
  printf '{"meshes": [{"file": "%s"}]}\n' "$path" >"$TMP/bad/scene.json"
  if "$WB" submit "$TMP/bad/scene.json" "${BAKE[@]}" --coordinator "$ADDR" >"$TMP/bad.log" 2>&1; then
    fail "a scene naming $path was accepted"
  fi
  grep -q "meshes\[0\].file" "$TMP/bad.log" || fail "the refusal of $path does not name meshes[0].file"
done
# A client that skips those checks (raw gRPC) is refused by the coordinator:
# a JSON scene loads only files uploaded with it, whatever path it names.
src=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
/usr/bin/python3 -m grpc_tools.protoc -I "$src/proto" --python_out="$TMP" \
  --grpc_python_out="$TMP" "$src/proto/wavebake.proto" || fail "protoc for Python"
/usr/bin/python3 - "$TMP" "$ADDR" "$TMP/bunny.obj" "$TMP/data" <<'PY' || fail "the coordinator accepted a scene naming files it was not given"
import sys
sys.path.insert(0, sys.argv[1])
import grpc
import wavebake_pb2 as pb
import wavebake_pb2_grpc as rpc
jobs = rpc.JobServiceStub(grpc.insecure_channel(sys.argv[2]))
def upload(name, data):
    return jobs.UploadScene(iter([pb.SceneChunk(file_name=name, data=data)]))
mesh = upload("other.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
cases = [  # (mesh path in the scene, the bundle's files, what the refusal names)
    (sys.argv[3], [], "meshes[0].file"),                        # absolute: the host's own file
    ("../bunny.obj", [], "meshes[0].file"),
    ("secret.obj", [("other.obj", mesh.sha256)], "meshes[0].file"),
    ("other.obj", [("../other.obj", mesh.sha256)], "scene.uploaded.files[0].path"),
]
for path, files, field in cases:
    scene = upload("scene.json", ('{"meshes": [{"file": "%s"}]}' % path).encode())
    for p, sha in files:
        scene.files.add(path=p, sha256=sha)
    try:
        jobs.Submit(pb.BakeRequest(scene=pb.SceneSource(uploaded=scene), light_res=8,
                                   layout="hilbert:8x8"))
    except grpc.RpcError as e:
        assert e.code() == grpc.StatusCode.INVALID_ARGUMENT, (path, e.code())
        assert field in e.details(), (path, e.details())
        # No path of the coordinator's data directory, beyond what the scene wrote.
        assert sys.argv[4] not in e.details().replace(path, ""), (path, e.details())
        continue
    raise SystemExit("accepted a scene naming %s" % path)
PY
echo "PASS: JSON scene with 2 mesh references baked from its upload alone; outside paths refused by client and coordinator"
