#!/usr/bin/env bash
# Separate hosts (DESIGN.md §4 data plane): the coordinator, two workers and
# a client each in a network namespace of their own, joined to the
# coordinator's by veth pairs with addresses of our own test hosts
# (10.213.k.0/30 inside these namespaces only), the store shared as a
# directory. Nothing can lean on 127.0.0.1 or on sharing a process: a worker's
# loopback has no coordinator, and the bake still ends byte-identical to an
# embedded one.
source "$(dirname "$0")/cluster_lib.bash" "$1"
command -v ip >/dev/null || fail "ip not found (iproute2)"
BAKE=(builtin:cubes-wall --layout camera:32x32 --light-res 16 --tile-size 8 --column-group 128)
"$WB" bake "${BAKE[@]}" --out "$TMP/ref.wbk" >"$TMP/ref.log" 2>&1 || fail "embedded bake failed"

ID=$$
C=wb${ID}c
NAMESPACES=("$C")
teardown() {
  local ns
  for ns in "${NAMESPACES[@]}"; do ip netns del "$ns" 2>/dev/null || true; done
}
trap 'cleanup; teardown' EXIT
ip netns add "$C" || fail "cannot create network namespace $C (needs root / CAP_NET_ADMIN)"
ip -n "$C" link set lo up
# host K gets 10.213.K.2, its link's far end in the coordinator's namespace 10.213.K.1
add_host() {
  local ns=$1 k=$2
  NAMESPACES+=("$ns")
  ip netns add "$ns"
  ip -n "$ns" link set lo up
  ip link add "wb${ID}v$k" netns "$C" type veth peer name eth0 netns "$ns"
  ip -n "$C" addr add "10.213.$k.1/30" dev "wb${ID}v$k"
  ip -n "$C" link set "wb${ID}v$k" up
  ip -n "$ns" addr add "10.213.$k.2/30" dev eth0
  ip -n "$ns" link set eth0 up
}
add_host "wb${ID}w1" 1
add_host "wb${ID}w2" 2
add_host "wb${ID}k" 3
# Not a function for the background processes: `ip netns exec` execs the
# program, so $! is its pid and cleanup can kill it.
in_ns() { ip netns exec "$@"; }

ip netns exec "$C" "$WB" coordinator --listen 0.0.0.0:7433 --data "$TMP/data" --lease-seconds 5 \
  --address-file "$TMP/coordinator.addr" >"$TMP/coordinator.log" 2>&1 &
PIDS+=($!)
wait_until 20 "the coordinator" test -s "$TMP/coordinator.addr"
for k in 1 2; do
  ip netns exec "wb${ID}w$k" "$WB" worker --coordinator "10.213.$k.1:7433" --store-root "$TMP/data/store" \
    --threads 1 --name "host$k" >"$TMP/w$k.log" 2>&1 &
  PIDS+=($!)
done
# A worker's own loopback has no coordinator behind it.
if in_ns "wb${ID}w1" timeout 20 "$WB" status --coordinator 127.0.0.1:7433 >"$TMP/lo.out" 2>&1; then
  fail "a worker host reached a coordinator on 127.0.0.1"
fi
K=(in_ns "wb${ID}k")
ADDR=10.213.3.1:7433
job=$("${K[@]}" "$WB" submit "${BAKE[@]}" --output-name netns.wbk --coordinator "$ADDR") ||
  fail "submit from the client host"
"${K[@]}" timeout 120 "$WB" watch "$job" --coordinator "$ADDR" >"$TMP/watch.log" 2>&1 ||
  fail "the bake did not finish: $(tail -n 3 "$TMP/watch.log")"
"${K[@]}" "$WB" fetch "$job" --out "$TMP/fetched.wbk" --coordinator "$ADDR" >/dev/null 2>&1 ||
  fail "fetch over the client's link"
same_store "$TMP/ref.wbk" "$TMP/data/store/netns.wbk"
same_store "$TMP/ref.wbk" "$TMP/fetched.wbk"
for k in 1 2; do log_has "$TMP/w$k.log" "done in" 1 || fail "worker host$k ran no task"; done
echo "PASS: coordinator, 2 workers and a client on 4 network namespaces; store byte-identical"
