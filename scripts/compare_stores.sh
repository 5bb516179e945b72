#!/usr/bin/env bash
# Bakes and relights the same small cases with two wavebake binaries and
# compares every output byte for byte (diff -r): the check that a refactoring
# changed no store and no relit picture. Usage:
#   scripts/compare_stores.sh OLD_BINARY NEW_BINARY [OUT_DIR]
# OUT_DIR (default out/compare) gets old/ and new/, one store (*.wbk) and its
# relit outputs per case. Exit status 0 when the two trees are identical.
set -euo pipefail
old=$1 new=$2 out=${3:-out/compare}
mkdir -p "$out"
repo=$(cd "$(dirname "$0")/.." && pwd)
data=${WB_SHARED_DATA:-$repo/../shared/data}
small=(--layout camera:32x32 --light-res 16)
export WAVEBAKE_SCENE_PATH=$data/models  # .ply outputs reload the mesh by its name

run() {  # run BINARY DIR: every case into DIR (stops at the first failure)
  local bin=$1 dir=$2
  rm -rf "$dir" && mkdir -p "$dir"
  for s in furnace disk-over-plane cylinder-bump cubes-wall sphere-plane; do
    "$bin" bake "builtin:$s" "${small[@]}" --out "$dir/$s.wbk"
    "$bin" relight "$dir/$s.wbk" --env builtin:sky --out "$dir/$s.exr"
  done
  "$bin" bake "$data/models/bunny.obj" --layout hilbert:64x64 --light-res 16 --out "$dir/bunny.wbk"
  "$bin" relight "$dir/bunny.wbk" --env builtin:sky --out "$dir/bunny.ply"
  "$bin" bake "$data/models/spot.obj" --layout uv:64x64 --light-res 16 --out "$dir/spot.wbk"
  "$bin" relight "$dir/spot.wbk" --env builtin:sky --out "$dir/spot.exr"
  "$bin" bake builtin:sphere-plane "${small[@]}" --transport visibility --out "$dir/vis.wbk"
  "$bin" relight "$dir/vis.wbk" --env builtin:sky --brdf phong:32 --out "$dir/vis_phong.exr"
  "$bin" bake builtin:cubes-wall "${small[@]}" --light-domain plane:4 --out "$dir/p4.wbk"
  "$bin" relight "$dir/p4.wbk" --area-light "$repo/docs/lights/softbox.json" --out "$dir/p4_near.exr"
}

# Each run in a bash of its own: set -e does not hold inside a function that
# is the left side of ||, and a failed case must not pass as identical.
cases() {  # cases BINARY DIR
  bash -euo pipefail -c "$(declare -p data small repo); $(declare -f run); run \"\$@\"" _ "$@"
}
cases "$old" "$out/old" >"$out.old.log" 2>&1 || { echo "old binary failed: $out.old.log"; exit 2; }
cases "$new" "$out/new" >"$out.new.log" 2>&1 || { echo "new binary failed: $out.new.log"; exit 2; }
echo "files compared: $(find "$out/old" -type f | wc -l)"
diff -r "$out/old" "$out/new" && echo "identical: every store and relit output"
