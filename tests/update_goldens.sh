#!/usr/bin/env bash
# Regenerates the golden images of tests/render_test.cpp. Run it only on
# purpose, after checking that a change of the pictures is intended:
#   tests/update_goldens.sh build/release/bounce
set -euo pipefail
bounce=${1:-build/release/bounce}
dir=$(cd "$(dirname "$0")" && pwd)/golden
common=(--size 128x128 --max-edge 60 --solver progressive)
"$bounce" render "${common[@]}" --max-steps 1 --out "$dir/cornell_1_shot.png" >/dev/null
"$bounce" render "${common[@]}" --max-steps 10 --out "$dir/cornell_10_shots.png" >/dev/null
"$bounce" render "${common[@]}" --until 0.001 --out "$dir/cornell_converged.png" >/dev/null
"$bounce" render --size 128x128 --until 0.001 --out "$dir/cornell_hierarchical.png" >/dev/null
"$bounce" trace "$dir/../../assets/whitted/whitted.json" --size 160x120 --spp 4 --no-radiosity --ambient 0.5 \
  --out "$dir/whitted_trace.png" >/dev/null
echo "goldens written to $dir"
