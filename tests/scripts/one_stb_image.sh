#!/usr/bin/env bash
# One stb_image in the process, the project's own: libdraco (pulled in by
# assimp) exports a copy of every stbi_* function, and a call by those public
# names was bound to it at run time: the truncated-.hdr hang of
# corrupt_inputs.sh was libdraco's stbi_loadf. runtime/io/stb_codecs.cc compiles
# Debian's header with internal linkage, so the binary must leave no stbi_*
# symbol for the dynamic linker to bind, to libdraco or anything else.
set -euo pipefail
WB=$1
fail() { echo "FAIL: $*" >&2; exit 1; }

undefined=$(nm -D --undefined-only "$WB" | grep -o 'stbi[a-z_]*' || true)
[[ -z $undefined ]] || fail "stb_image symbols left to the dynamic linker: $(echo $undefined)"
# The run-time view of the same: every symbol bound at start (LD_BIND_NOW),
# none of them an stbi_* of another object.
bound=$(LD_BIND_NOW=1 LD_DEBUG=bindings "$WB" --help 2>&1 >/dev/null |
  grep -E "binding file [^ ]*wavebake .*symbol \`stbi" || true)
[[ -z $bound ]] || fail "stb_image bound outside the binary: $bound"
echo "PASS: no stbi_* symbol of wavebake resolves outside it"
