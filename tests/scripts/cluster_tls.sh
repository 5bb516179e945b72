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
echo "PASS: TLS coordinator, worker and client; plaintext refused"
