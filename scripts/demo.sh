#!/usr/bin/env bash
# The README's demo: bake a built-in scene on the embedded default and write a
# picture of it relit under a procedural sky. Outputs land in ./out/.
set -euo pipefail
bin=${1:-build/wavebake}
mkdir -p out
"$bin" bake builtin:sphere-plane --layout camera:128x128 --light-res 32 --out out/demo.wbk
"$bin" relight out/demo.wbk --env builtin:sky --terms 256 --out out/demo.png
echo "demo: wrote out/demo.wbk and out/demo.png"
