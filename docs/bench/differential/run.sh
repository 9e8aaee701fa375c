#!/bin/bash
# The full sweep of the randomized differential test (issue 27, item 1): every technique and each of its enumerated
# parameter choices against the Embree reference on random scenes (scene/RandomScenes.h), held to each technique's
# accuracy contract (TechniqueDescriptor::accuracy; docs/accuracy.md). From the
# repository root:
#   bash docs/bench/differential/run.sh [FIRST LAST]     (default seeds 1..6)
# Writes docs/bench/differential/run/ (report.md: the table per technique and every failed configuration with its
# seed and the command that reproduces it; differential.json; seed-S/scene.json) and the console log run.log.
# Sized for the 2-core machine shared with other jobs: 64-pixel images (the generator's drawn sizes scaled down), 256
# reference samples; one seed takes 2-4 minutes for all 16 techniques and their ~120 choices. A copy of the binary
# keeps one build for the whole run (other sessions relink build/shadowlab).
set -uo pipefail
D=docs/bench/differential
SL=${SHADOWLAB:-build/shadowlab}
FIRST=${1:-1}
LAST=${2:-6}
start=$(date +%s)
"$SL" differential --seeds "$FIRST..$LAST" --max-side 64 --reference-samples 256 --out "$D/run" --force -q 2>&1 | tee "$D/run.log"
status=${PIPESTATUS[0]}
echo "wall time: $(( $(date +%s) - start )) s, exit $status" | tee -a "$D/run.log"
