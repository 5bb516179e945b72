#!/usr/bin/env bash
# `wavebake bake --serve`: the embedded bake's monitor follows the bake, then
# keeps serving the finished store (its relight view) until SIGINT, and the
# bake still exits 0 with its store at --out. A mesh layout: the picture is a
# vertex-colour rendering of the scene.
set -euo pipefail
WB=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
TMP=$(mktemp -d "${TMPDIR:-/tmp}/wb_bake_serve.XXXXXX")
PID=
cleanup() {
  [[ -n $PID ]] && kill -9 "$PID" 2>/dev/null || true
  rm -rf "$TMP"
}
trap cleanup EXIT
echo serve-token > "$TMP/token"
"$WB" bake builtin:furnace --layout grid --light-res 8 --tile-size 16 --out "$TMP/f.wbk" --quiet \
  --serve 127.0.0.1:0 --serve-address-file "$TMP/addr" --token-file "$TMP/token" \
  > "$TMP/out.log" 2> "$TMP/err.log" &
PID=$!
/usr/bin/python3 - "$TMP" <<'PY'
import json, sys, time, urllib.request, urllib.error
from pathlib import Path
tmp = Path(sys.argv[1])
deadline = time.time() + 60
while not (tmp / "addr").exists():
    assert time.time() < deadline, "no address file"
    time.sleep(0.05)
base = "http://" + (tmp / "addr").read_text().strip()
def get(path, token=True):
    req = urllib.request.Request(base + path)
    if token:
        req.add_header("Authorization", "Bearer serve-token")
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers, e.read()
assert get("/api/jobs", token=False)[0] == 401
while True:
    status, _, body = get("/api/jobs")
    jobs = json.loads(body) if status == 200 else []
    if jobs and jobs[0]["phase"] == "DONE":
        break
    assert time.time() < deadline, f"bake not DONE: {status} {body[:200]}"
    time.sleep(0.1)
job = jobs[0]["id"]
while not (tmp / "f.wbk" / ".zattrs").exists():  # published just after the job ends
    assert time.time() < deadline, "the store is not at --out"
    time.sleep(0.05)
status, headers, png = get(f"/api/jobs/{job}/relight?probe=builtin:sky&format=png")
assert status == 200 and png[1:4] == b"PNG", (status, png[:100])
assert headers["X-Picture"] == "vertex colours", headers["X-Picture"]
status, _, store = get(f"/api/jobs/{job}/store")
assert status == 200 and json.loads(store)["layout"] == "grid", store
status, _, metrics = get("/metrics")
assert b"wavebake_jobs{phase=\"done\"} 1" in metrics, metrics[:400]
print("bake --serve: DONE job", job, "relit as", headers["X-Picture"])
PY
kill -INT "$PID"
rc=0; wait "$PID" || rc=$?
PID=
[[ $rc == 0 ]] || { cat "$TMP/err.log" >&2; echo "FAIL: bake --serve exited $rc after SIGINT" >&2; exit 1; }
grep -q "web monitor at http://127.0.0.1:" "$TMP/err.log" || { cat "$TMP/err.log" >&2; exit 1; }
[[ -f $TMP/f.wbk/.zattrs ]] || { echo "FAIL: no store at --out" >&2; exit 1; }
echo "bake --serve: OK"
