#!/usr/bin/env bash
# `bake --out` where the path is not plain: a symbolic link is followed (the
# store goes to its target; it used to fail with "INTERNAL: rename … Not a
# directory"), and a store holding a file no bake writes is not replaced (it
# used to be deleted with the store, without a word).
set -euo pipefail
WB=$1
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
BAKE=(builtin:cubes-wall --layout camera:16x16 --light-res 8 --quiet)

mkdir "$TMP/disk"
ln -s disk/real.wbk "$TMP/link.wbk"
"$WB" bake "${BAKE[@]}" --out "$TMP/link.wbk" >"$TMP/out.txt" 2>&1 || fail "via a dangling link: $(cat "$TMP/out.txt")"
[[ -L $TMP/link.wbk && -f $TMP/disk/real.wbk/.zattrs ]] || fail "the store is not at the link's target"
"$WB" bake "${BAKE[@]}" --out "$TMP/link.wbk" >"$TMP/out.txt" 2>&1 || fail "replacing via the link: $(cat "$TMP/out.txt")"
[[ -L $TMP/link.wbk ]] || fail "the link was replaced by a directory"
[[ -z $(ls -A "$TMP/disk" | grep -v '^real.wbk$') ]] || fail "left beside the target: $(ls -A "$TMP/disk")"

echo "my notes" >"$TMP/disk/real.wbk/notes.txt"
if "$WB" bake "${BAKE[@]}" --out "$TMP/link.wbk" >"$TMP/out.txt" 2>&1; then
  fail "replaced a store holding a user's file"
fi
grep -qF "ALREADY_EXISTS: out: the store" "$TMP/out.txt" || fail "$(cat "$TMP/out.txt")"
grep -qF "notes.txt, which no bake writes" "$TMP/out.txt" || fail "$(cat "$TMP/out.txt")"
[[ $(cat "$TMP/disk/real.wbk/notes.txt") == "my notes" ]] || fail "the user's file is gone"
[[ -z $(ls -A "$TMP/disk" | grep -v '^real.wbk$') ]] || fail "left beside the target: $(ls -A "$TMP/disk")"
echo "PASS: --out through a link bakes at its target; a store with a user's file is not replaced"
