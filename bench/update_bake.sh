#!/usr/bin/env bash
# Update bakes against full bakes, in the same run (worker/tiles/row_reuse.h):
# for each scene pair (a -> b: one small object moved) a store of a is baked
# with --keep-staging, then b is baked in full, with --update-exact and with
# --update from a's store; an unchanged scene is updated too. Prints wall
# and CPU seconds and their ratios to the full bake's, checks that the
# --update-exact store is byte-identical to the full bake's (all files; the
# .zattrs once its "update" record is set aside) and, with --eval, the
# eval --reference error of --update against the full bake's (builtin:sky;
# rel. SE 0.01 with --bounces).
#
#   bench/update_bake.sh [build/wavebake] [WORK_DIR] [--quick] [--eval] [--bounces B]
#
# Scenes (bench/update_scenes.py): bunny + spot on a ground grid with a
# small cube moved (hilbert:128x128, N = 32) and cubes-wall-like geometry
# with one corner cube moved (camera:256x256, N = 32). --quick: N = 16,
# hilbert:128x128 (the two models have 8128 vertices) and camera:128x128.
# Targets: --update <= 0.25x, --update-exact <= 0.35x of the full bake's wall
# time. --bounces B bakes every store with B bounces (an update then reuses
# direct rows only and codes every column: docs/UPDATE.md).
set -euo pipefail
WB=$(realpath "${1:-build/wavebake}")
WORK=${2:-$(mktemp -d "${TMPDIR:-/tmp}/wb_update.XXXXXX")}
shift $(($# >= 2 ? 2 : $#)) || true
quick=0 eval=0 bounces=0
while (($#)); do
  case $1 in
    --quick) quick=1 ;;
    --eval) eval=1 ;;
    --bounces) bounces=$2 && shift ;;
  esac
  shift
done
here=$(cd "$(dirname "$0")" && pwd)
models=$(realpath "$here/../../shared/data/models")
py=/usr/bin/python3
mkdir -p "$WORK"
"$py" "$here/update_scenes.py" "$WORK/scenes" "$models"
cd "$WORK/scenes"

# timed NAME CMD...: runs CMD, appends "NAME wall user sys" to $WORK/times
timed() {
  local name=$1
  shift
  /usr/bin/time -f "$name %e %U %S" -a -o "$WORK/times" "$@" >"$WORK/$name.log" 2>&1
}
seconds() { awk -v n="$1" '$1 == n {printf "%.2f %.2f", $2, $3 + $4}' "$WORK/times"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.3f", a / b}'; }

same_store() { # FULL UPDATED: byte-identical but for .zattrs' "update"
  diff -r -x .zattrs "$1" "$2" >/dev/null || {
    echo "DIFFERENT files"
    return
  }
  "$py" - "$1/.zattrs" "$2/.zattrs" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
b.pop("update", None)
print("byte-identical" if a == b else "DIFFERENT .zattrs")
PY
}
record() {
  "$py" - "$1/.zattrs" <<'PY'
import json, sys
u = json.load(open(sys.argv[1]))["update"]
keys = ("rows", "rows_reused", "rows_patched", "rows_rebaked", "columns_recomputed", "columns_depth_searched", "columns")
print(" ".join("%s=%s" % (k, u.get(k)) for k in keys))
PY
}
# With bounces the reference is path-traced, and eval's default standard
# error (0.002) took over six minutes on the cubes-wall-like store: 0.01 then.
ref_se=()
((bounces > 0)) && ref_se=(--reference-se 0.01)
ref_error() {
  "$WB" eval "$1" --env builtin:sky --reference "${ref_se[@]}" --no-dense --json 2>/dev/null |
    "$py" -c "import json,sys; print('%.5f' % json.load(sys.stdin)['compressed']['rel_rms'])"
}

run_case() { # NAME SCENE_A SCENE_B FLAGS...
  local name=$1 a=$2 b=$3
  shift 3
  local flags=("$@" --bounces "$bounces" --keep-staging --quiet --workers 2)
  rm -f "$WORK/times"
  rm -rf "$WORK/$name".*.wbk
  timed old "$WB" bake "$a" "${flags[@]}" --out "$WORK/$name.old.wbk"
  timed full "$WB" bake "$b" "${flags[@]}" --out "$WORK/$name.full.wbk"
  timed exact "$WB" bake "$b" "${flags[@]}" --update "$WORK/$name.old.wbk" --update-exact \
    --out "$WORK/$name.exact.wbk"
  timed local "$WB" bake "$b" "${flags[@]}" --update "$WORK/$name.old.wbk" \
    --out "$WORK/$name.local.wbk"
  timed same "$WB" bake "$a" "${flags[@]}" --update "$WORK/$name.old.wbk" \
    --out "$WORK/$name.same.wbk"
  local fw fc w c
  read -r fw fc <<<"$(seconds full)"
  echo "== $name: $a -> $b (${*})"
  printf "%-8s %8s %8s %8s %8s\n" run wall_s cpu_s x_wall x_cpu
  for r in full exact local same; do
    read -r w c <<<"$(seconds $r)"
    printf "%-8s %8s %8s %8s %8s\n" "$r" "$w" "$c" "$(ratio "$w" "$fw")" "$(ratio "$c" "$fc")"
  done
  echo "--update-exact vs full: $(same_store "$WORK/$name.full.wbk" "$WORK/$name.exact.wbk")"
  echo "--update-exact record: $(record "$WORK/$name.exact.wbk")"
  echo "--update record:       $(record "$WORK/$name.local.wbk")"
  echo "unchanged record:      $(record "$WORK/$name.same.wbk")"
  if [[ $eval == 1 ]]; then
    echo "eval --reference rel_rms (builtin:sky): full $(ref_error "$WORK/$name.full.wbk")," \
      "--update $(ref_error "$WORK/$name.local.wbk")"
  fi
}

if [[ $quick == 1 ]]; then
  run_case bunny_spot bunny_spot_a.json bunny_spot_b.json --layout hilbert:128x128 --light-res 16
  run_case wall_cubes wall_cubes_a.json wall_cubes_b.json --layout camera:128x128 --light-res 16
else
  run_case bunny_spot bunny_spot_a.json bunny_spot_b.json --layout hilbert:128x128 --light-res 32
  run_case wall_cubes wall_cubes_a.json wall_cubes_b.json --layout camera:256x256 --light-res 32
fi
