#!/usr/bin/env bash
# cli/ is the thin front end of DESIGN.md §6: everything it runs is behind
# driver/ (and the web monitor it starts, web/, which sits on driver/). Fails
# when a file of cli/ includes a project header of any other layer (core/,
# storage/, worker/, coordinator/, runtime/, proto/ or a generated *.pb.h);
# third-party headers (<...>, "absl/...") are fine.
set -euo pipefail
src=${WB_SOURCE_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}
bad=$(grep -HnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$src"/cli/*.h "$src"/cli/*.cc \
        "$src"/cli/*.cpp | grep -vE '#[[:space:]]*include[[:space:]]*"(cli|driver|web|absl)/' || true)
if [ -n "$bad" ]; then
  echo "cli/ includes past driver/ and web/:" >&2
  echo "$bad" >&2
  exit 1
fi
echo "cli/ includes cli/, driver/, web/ and third-party headers only"
