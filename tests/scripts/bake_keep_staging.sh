#!/usr/bin/env bash
# `wavebake bake --keep-staging` (issue "Column stage"): FINALIZE leaves the
# staging arrays in the store, python zarr reads them, and the transport is
# byte-identical to a bake without the flag (which leaves no staging).
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
args=(builtin:disk-over-plane --layout camera:16x16 --light-res 8 --quiet)
"$WB" bake "${args[@]}" --out "$TMP/plain.wbk" >/dev/null
"$WB" bake "${args[@]}" --keep-staging --out "$TMP/kept.wbk" >/dev/null
[ ! -e "$TMP/plain.wbk/staging" ] || fail "staging left without --keep-staging"
[ -d "$TMP/kept.wbk/staging/transport" ] || fail "--keep-staging did not keep staging/transport"
diff -r "$TMP/plain.wbk/transport" "$TMP/kept.wbk/transport" >/dev/null ||
  fail "--keep-staging changed the transport arrays"
/usr/bin/python3 - "$TMP/kept.wbk" <<'PY' || fail "python zarr cannot read the kept staging"
import sys, zarr
g = zarr.open(sys.argv[1], mode="r")
staged = g["staging/transport"]
assert staged.shape == (6 * 8 * 8, 16 * 16), staged.shape
assert abs(float((staged[:] ** 2).sum()) - float(g["staging/tile_energy"][:].sum())) < 1e-3
PY
echo "PASS: --keep-staging keeps readable staging and the same transport"
