#!/bin/bash
# ss08's defaults on held-out scenes (issue 27). From the repository root:
#   bash docs/bench/ss08-defaults/run.sh [settings] [budget]   (no argument: both)
# The four scenes here (three-plates, near-gap, overlap-squares, wide-light) are parallel rectangles under a square
# light that no test or dataset holds; 128 x 128 frames, the default 1024^2 map, 1024-sample Embree references.
#  settings: ss08's micro-occluders x accumulations beside vssm, dcs and penumbra-wedge at their defaults;
#  budget:   ss08 at its defaults over budgets 3, 5, 9, 12, 16.
#  front:    ss08, vssm, dcs and penumbra-wedge at their defaults on two meshed datasets (bunny, fence-meshed), 128 x 128.
# Made on 2026-12-03: `settings` with build/shadowlab of 0aa3f6f from a copy of the scene directories (bench.csv names
# them relatively), `budget` with 9377c3f's parent (the microrect+bitmask defaults, 1db28c0) by this script; `front`
# on 2026-12-04 with build/shadowlab of 74c322a, alone on the machine.
# Timings come from llvmpipe on a 2-core machine shared with builds and other benches: compare ratios within one run.
set -euo pipefail
D=docs/bench/ss08-defaults
SL=${SHADOWLAB:-build/shadowlab}
CACHE="--cache /tmp/slcache-ss08-defaults"
SCENES="$D/near-gap/scene.json $D/overlap-squares/scene.json $D/three-plates/scene.json $D/wide-light/scene.json"
for part in ${*:-settings budget front}; do
  case $part in
  settings)
    "$SL" bench $SCENES -t ss08,vssm,dcs,penumbra-wedge --sweep micro_occluder=micropatch,microrect \
      --sweep accumulation=area,bitmask --repeat 2 -r 128x128 $CACHE -o $D/settings --force
    ;;
  budget)
    "$SL" bench $SCENES -t ss08 --sweep budget=3,5,9,12,16 --repeat 2 -r 128x128 $CACHE -o $D/budget --force
    ;;
  front)
    "$SL" bench datasets/bunny/scene.json datasets/fence-meshed/scene.json -t ss08,vssm,dcs,penumbra-wedge --repeat 2 \
      -r 128x128 $CACHE -o $D/front --force
    ;;
  esac
done
