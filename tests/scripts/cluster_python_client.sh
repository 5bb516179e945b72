#!/usr/bin/env bash
# DESIGN.md §4 for any language: a Python client generated from proto/ with
# grpc_tools.protoc (python3-grpc-tools) uploads a scene, submits a job,
# watches it to completion and fetches the store; python zarr opens it.
source "$(dirname "$0")/cluster_lib.bash" "$1"
src=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}

/usr/bin/python3 -m grpc_tools.protoc -I "$src/proto" --python_out="$TMP" \
  --grpc_python_out="$TMP" "$src/proto/wavebake.proto" || fail "protoc for Python"
echo "python-token" >"$TMP/token"
start_coordinator "$TMP/data" "$(free_port)" --token-file "$TMP/token"
start_worker w1 "$TMP/data/store" --threads 2 --token-file "$TMP/token"
timeout 120 /usr/bin/python3 "$(dirname "$0")/cluster_client.py" "$TMP" "$ADDR" "$TMP/token" \
  "$TMP/fetched.wbk" || fail "the Python client"
echo "PASS: Python client submitted, watched, fetched; zarr opened the store"
