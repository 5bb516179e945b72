#!/usr/bin/env bash
# DESIGN.md §4 "TLS when certs are given": a coordinator serving a
# certificate signed by a test CA; a worker and a client given that CA
# (--tls-ca) bake a job; a client given another CA, and a plaintext client,
# are refused: certificates are verified, not merely present.
source "$(dirname "$0")/cluster_lib.bash" "$1"

ssl() { openssl "$@" >/dev/null 2>&1 || fail "openssl $1 could not make a test certificate"; }
make_ca() {  # make_ca NAME: NAME.key, NAME.pem, a self-signed CA
  ssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj "/CN=$1 test CA" \
    -addext basicConstraints=critical,CA:TRUE -keyout "$TMP/$1.key" -out "$TMP/$1.pem"
}
make_ca ca
make_ca other
ssl req -newkey rsa:2048 -nodes -subj /CN=localhost -keyout "$TMP/server.key" -out "$TMP/server.csr"
printf 'subjectAltName=DNS:localhost,IP:127.0.0.1\n' >"$TMP/san.ext"
ssl x509 -req -in "$TMP/server.csr" -CA "$TMP/ca.pem" -CAkey "$TMP/ca.key" -CAcreateserial \
  -days 1 -extfile "$TMP/san.ext" -out "$TMP/server.pem"

start_coordinator "$TMP/data" "$(free_port)" --tls-cert "$TMP/server.pem" --tls-key "$TMP/server.key"
start_worker w1 "$TMP/data/store" --threads 2 --tls-ca "$TMP/ca.pem"

job=$("$WB" submit builtin:furnace --light-res 8 --layout camera:16x16 --coordinator "$ADDR" \
  --tls-ca "$TMP/ca.pem")
timeout 60 "$WB" watch "$job" --coordinator "$ADDR" --tls-ca "$TMP/ca.pem" >/dev/null 2>&1 ||
  fail "the job did not complete over TLS"
"$WB" status "$job" --coordinator "$ADDR" --tls-ca "$TMP/ca.pem" >/dev/null 2>"$TMP/err.txt" ||
  fail "a client trusting the right CA was refused: $(cat "$TMP/err.txt")"

if timeout 30 "$WB" status --coordinator "$ADDR" --tls-ca "$TMP/other.pem" >/dev/null \
  2>"$TMP/err.txt"; then
  fail "a client trusting another CA was served"
fi
grep -q UNAVAILABLE "$TMP/err.txt" || fail "client with another CA: $(cat "$TMP/err.txt")"
if "$WB" status --coordinator "$ADDR" >/dev/null 2>"$TMP/err.txt"; then
  fail "a plaintext client was served by a TLS coordinator"
fi
grep -q UNAVAILABLE "$TMP/err.txt" || fail "plaintext client: $(cat "$TMP/err.txt")"

# A worker that does not trust the coordinator's certificate ends, non-zero,
# naming the certificate problem, after a few tries (it used to retry forever).
rc=0
timeout 30 "$WB" worker --coordinator "$ADDR" --store-root "$TMP/data/store" \
  --tls-ca "$TMP/other.pem" >"$TMP/wrong-ca.log" 2>&1 || rc=$?
((rc != 124)) || fail "a worker with the wrong CA was still retrying after 30 s"
((rc != 0)) || fail "a worker with the wrong CA exited 0"
grep -q "TLS: no trusted connection.*certificate verify failed" "$TMP/wrong-ca.log" ||
  fail "wrong CA: $(tail -3 "$TMP/wrong-ca.log")"
echo "PASS: TLS with the right CA; another CA and plaintext refused; a wrong CA ends the worker"
