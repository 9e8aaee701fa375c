#!/bin/bash
# dcs (depth complexity sampling; FBP08 via Forest et al. 2009 §3.2, §4.1): the bench of issue 16, item 5. From the
# repository root:
#   bash docs/bench/dcs/run.sh [patterns] [patterns-offset] [receiver-offset] [light-size-bunny]
#     [light-size-near-light] [patterns-near-light] [memory] [table]
#   (no argument: all)
# Every `bench` writes its own sub-directory through --out (bench replaces it atomically). Timings come from
# llvmpipe on a 2-core machine shared with other jobs: compare ratios within one run, not absolute milliseconds
# across runs. References: the bench's ray-traced reference at 1024 light samples (--reference-samples 1024, its default
# sampling), cached outside the repository.
# The committed outputs were made on 2026-12-02 with SHADOWLAB=/tmp/dcsbench3/shadowlab, a copy of build/shadowlab
# built from the commit that added them (dcs's wedge hulls as in "dcs: wedge hulls scaled to the scene box's deepest
# point", receiver_offset 1e-4): other sessions relink build/shadowlab while a bench runs, and a first run lost 7
# configurations to "cannot start a child process" when that happened.
set -euo pipefail
D=docs/bench/dcs
SL=${SHADOWLAB:-build/shadowlab}
CACHE="--cache /tmp/slcache-dcs"
PARTS=${*:-patterns patterns-offset receiver-offset light-size-bunny light-size-near-light patterns-near-light memory table}
PATTERNS=grid,stratified,poisson,zero_two,grid_4x4,stratified_4x4,poisson_4x4,zero_two_4x4

for part in $PARTS; do
  case $part in
  patterns)
    # Forest et al. 2009 Fig. 5's kind: every light-sample pattern (and its 4x4-interleaved variant) at N = 16 and 64,
    # RMSE against the 1024-sample reference, on bunny and planar-occluder; N = 256 too, to show where the
    # reference's own noise (1024 samples) sets the floor.
    "$SL" bench datasets/bunny/scene.json datasets/planar-occluder/scene.json -t dcs \
      --sweep light_samples=$PATTERNS --sweep samples=16,64,256 -r 256x256 --repeat 3 --reference-samples 1024 $CACHE \
      --out $D/patterns
    ;;
  patterns-offset)
    # The bunny's pattern table again at receiver_offset = 1e-5, dcs's first default (shadow-volume's): ~160 pixels
    # on the bunny's body (sample segments that re-enter the faceted surface near the visible point) keep a bias
    # that no N removes, which made the default 1e-4 (see receiver-offset).
    "$SL" bench datasets/bunny/scene.json -t dcs -s receiver_offset=1e-5 \
      --sweep light_samples=$PATTERNS --sweep samples=16,64,256 -r 256x256 --repeat 3 --reference-samples 1024 $CACHE \
      --out $D/patterns-offset
    ;;
  receiver-offset)
    # receiver_offset (the visible point moved this fraction of its eye distance toward the camera) on bunny,
    # poisson at N = 64 and 256: where the self-shadowing bias ends and light leaks begin.
    "$SL" bench datasets/bunny/scene.json -t dcs --sweep receiver_offset=0,1e-5,3e-5,1e-4,3e-4,1e-3 \
      --sweep samples=64,256 -r 256x256 --repeat 3 --reference-samples 1024 $CACHE --out $D/receiver-offset
    ;;
  light-size-bunny)
    # Time and RMSE over light sizes beside gbp07, yfgl09 and pcss (their defaults); dcs at its default pattern
    # (poisson) with N = 16 and 64. One bench, so each speed_vs_error chart holds all four techniques.
    "$SL" bench datasets/bunny/scene.json -t dcs,gbp07,yfgl09,pcss --sweep samples=16,64 \
      --scene-sweep /lights/0/size=0.1,0.3,0.6,1.2,2.4 -r 256x256 --repeat 3 --reference-samples 1024 $CACHE \
      --out $D/light-size-bunny
    ;;
  light-size-near-light)
    # The same on near-light (default light size 1) at 128x128 and three sizes: at 256x256 and size 1 one
    # gbp07 frame took 85 s (41436 pixels cut short) and one yfgl09 frame 17 s, beyond this bench's budget.
    "$SL" bench datasets/near-light/scene.json -t dcs,gbp07,yfgl09,pcss --sweep samples=16,64 \
      --scene-sweep /lights/0/size=0.25,0.5,1 -r 128x128 --repeat 3 --reference-samples 1024 $CACHE \
      --out $D/light-size-near-light
    ;;
  patterns-near-light)
    # The patterns on near-light at its own light size (1) and light-size-near-light's 128x128: whether a better
    # pattern than the default poisson brings dcs's sampling noise below pcss's error there.
    "$SL" bench datasets/near-light/scene.json -t dcs --sweep light_samples=$PATTERNS --sweep samples=16,64,256 \
      -r 128x128 --repeat 3 --reference-samples 1024 $CACHE --out $D/patterns-near-light
    ;;
  memory)
    # sample_buffer_bytes and paper_sample_buffer_bytes for N = 16, 64, 256 at 256x256 (one render each; bench
    # keeps technique_statistics too, but N = 256 is in no bench above).
    OUT=$(mktemp -d)
    for N in 16 64 256; do
      "$SL" render datasets/bunny/scene.json -t dcs -s samples=$N -r 256x256 -q -o "$OUT/n$N"
    done
    python3 - "$OUT" > $D/memory.json <<'PY'
import json, os, sys
rows = []
for N in (16, 64, 256):
    stats = json.load(open(os.path.join(sys.argv[1], f"n{N}", "stats.json")))
    statistics = stats["technique_statistics"]
    rows.append({"samples": N, "resolution": stats["resolution"],
                 "sample_buffer_bytes": statistics["sample_buffer_bytes"],
                 "paper_sample_buffer_bytes": statistics["paper_sample_buffer_bytes"]})
print(json.dumps(rows, indent=1))
PY
    rm -rf "$OUT"
    ;;
  table)
    python3 $D/table.py > $D/tables.md
    ;;
  *)
    echo "unknown part: $part" >&2
    exit 2
    ;;
  esac
done
