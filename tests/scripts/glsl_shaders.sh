#!/usr/bin/env bash
# The viewer's GLSL ES 3.00 shaders (web/static/*.frag, *.vert) compile with
# Khronos' reference front end, glslangValidator (Debian glslang-tools); a
# copy with a type error must not, so a validator that accepts anything
# fails the test.
set -euo pipefail
SRC=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
V=$(command -v glslangValidator) || { echo "glslangValidator missing: scripts/setup.sh installs glslang-tools"; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
n=0
for f in "$SRC"/web/static/*.frag "$SRC"/web/static/*.vert; do
  [ -e "$f" ] || continue
  head -1 "$f" | grep -qx '#version 300 es' || { echo "$f: not GLSL ES 3.00"; exit 1; }
  "$V" "$f" >"$TMP/log" || { cat "$TMP/log"; echo "FAIL: $f"; exit 1; }
  n=$((n + 1))
  # The same shader with a float assigned to an int must be refused.
  ext=${f##*.}
  sed '0,/^void main() {/s//void main() { int broken = 1.5;/' "$f" >"$TMP/broken.$ext"
  if "$V" "$TMP/broken.$ext" >/dev/null; then echo "FAIL: the validator accepted a broken copy of $f"; exit 1; fi
done
[ "$n" -gt 0 ] || { echo "no shaders found under $SRC/web/static"; exit 1; }
echo "ok: $n shaders validate"
