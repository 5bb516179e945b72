#!/usr/bin/env bash
# deploy/k8s checked offline (there is no cluster here): schema, wiring and a
# rehearsal of the containers' own commands (tests/scripts/k8s_check.py).
source "$(dirname "$0")/cluster_lib.bash" "$1"
SRC=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
/usr/bin/python3 -c 'import kubernetes, yaml' 2>/dev/null ||
  fail "python3-kubernetes not found (scripts/setup.sh installs it)"
/usr/bin/python3 "$(dirname "$0")/k8s_check.py" "$WB" "$SRC/deploy/k8s" "$TMP" "$SRC"
