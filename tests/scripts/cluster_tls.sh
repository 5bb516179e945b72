#!/usr/bin/env bash
# DESIGN.md §4 "TLS when certs are given": a coordinator serving TLS; a worker
# and a client trusting its certificate (--tls-ca) bake a job; a client that
# does not trust it cannot talk to it.
source "$(dirname "$0")/cluster_lib.bash" "$1"

openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost \
  -addext subjectAltName=DNS:localhost,IP:127.0.0.1 -keyout "$TMP/key.pem" \
  -out "$TMP/cert.pem" >/dev/null 2>&1 || fail "openssl could not make a test certificate"
start_coordinator "$TMP/data" "$(free_port)" --tls-cert "$TMP/cert.pem" --tls-key "$TMP/key.pem"
start_worker w1 "$TMP/data/store" --threads 2 --tls-ca "$TMP/cert.pem"

job=$("$WB" submit builtin:furnace --light-res 8 --layout camera:16x16 --coordinator "$ADDR" \
  --tls-ca "$TMP/cert.pem")
timeout 60 "$WB" watch "$job" --coordinator "$ADDR" --tls-ca "$TMP/cert.pem" >/dev/null 2>&1 ||
  fail "the job did not complete over TLS"
if "$WB" status --coordinator "$ADDR" >/dev/null 2>"$TMP/err.txt"; then
  fail "a plaintext client was served by a TLS coordinator"
fi
grep -q UNAVAILABLE "$TMP/err.txt" || fail "plaintext client: $(cat "$TMP/err.txt")"

# A worker that does not trust the coordinator's certificate ends, non-zero,
# naming the certificate problem, after a few tries (it used to retry forever).
openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost \
  -addext subjectAltName=DNS:localhost,IP:127.0.0.1 -keyout "$TMP/other-key.pem" \
  -out "$TMP/other.pem" >/dev/null 2>&1 || fail "openssl could not make a second certificate"
rc=0
timeout 30 "$WB" worker --coordinator "$ADDR" --store-root "$TMP/data/store" \
  --tls-ca "$TMP/other.pem" >"$TMP/wrong-ca.log" 2>&1 || rc=$?
((rc != 124)) || fail "a worker with the wrong CA was still retrying after 30 s"
((rc != 0)) || fail "a worker with the wrong CA exited 0"
grep -q "TLS: no trusted connection.*certificate verify failed" "$TMP/wrong-ca.log" ||
  fail "wrong CA: $(tail -3 "$TMP/wrong-ca.log")"
echo "PASS: TLS coordinator, worker and client; plaintext refused; a wrong CA ends the worker"
