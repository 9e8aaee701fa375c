#!/bin/bash
# Soft textured shadow volumes (Forest et al. 2009): the claims of issue 18, item 4. From the repository
# root:
#   bash docs/bench/stsv/run.sh [fence] [fence-dcs] [meshed] [references] [coverage] [fence-512] [fence-dcs-512]
#     [meshed-512] [rerun] [spread] [table]
#   (no argument: all)
# - Fig. 11 (§6: 2 perforated triangles with STSV at 90 fps against the 233 358-triangle mesh with DCS16 at
#   3.3 fps, 27x) and the 25-35x of the abstract / §1: the technique stage of penumbra-wedge (PWedge+STSV)
#   and dcs (dcs+STSV) on `fence` against dcs (and penumbra-wedge) on `fence-meshed`, the same fence meshed along
#   texel boundaries (63 488 triangles of canopy), same light samples (poisson, N = 16 and 64).
# - Figs. 2, 4, 10 as numbers: RMSE against the ray tracer (Embree, 1024 stratified samples, alpha-tested) on
#   `fence` of PWedge+STSV, dcs+STSV, dcs on the mesh and gbp07 at a 1024^2 shadow map (Fig. 2's SSM 1024^2).
# - Fig. 9's kind: the per-step GPU times (volumes, wedges, STSV, resolve) from each run's technique_statistics.
# Every `bench` writes its own sub-directory through --out (bench replaces it atomically). 256x256 so that the whole
# run stays near 15 minutes on the 2-core machine (one dcs frame on fence-meshed takes 3-6 s at N = 16 and 4-10 s at
# N = 64 there); the *-512 parts repeat the timings at 512x512 to show how the ratio moves with the image size.
# Timings come from llvmpipe (Mesa's CPU rasteriser) on a 2-core machine shared with other jobs: compare ratios
# within one run, not absolute milliseconds across runs.
# The committed outputs were made on 2026-12-02 with SHADOWLAB=/tmp/stsvbench2/shadowlab, a copy of build/shadowlab
# built for commit 133b516 (dcs + STSV), starting from an empty reference cache; which parts were rerun and under
# what load: summary.md. Other sessions relink build/shadowlab while a bench runs; a copy keeps one binary.
set -euo pipefail
D=docs/bench/stsv
SL=${SHADOWLAB:-build/shadowlab}
CACHE="--cache /tmp/slcache-stsv"
PARTS=${*:-fence fence-dcs meshed references coverage fence-512 fence-dcs-512 meshed-512 rerun spread table}
# The paper's pattern (Forest et al. 2009 §4.1), set explicitly so that a change of a technique's default cannot split the
# two sides of the ratio (bench refuses a --set no technique of the run has, so gbp07's map size is set in `fence`).
COMMON="-s light_samples=poisson --reference-samples 1024 $CACHE"

for part in $PARTS; do
  case $part in
  fence)
    # PWedge+STSV at N = 16 and 64 (the paper's PWedge+STSV64 and the same at 16) and gbp07 at 1024^2 on the
    # perforated fence (two S-triangles; the ground quad's four boundary edges are the only wedges). gbp07 has
    # neither light_samples nor samples and runs once, at a 1024^2 map (Fig. 2 a's "SSM 1024^2").
    "$SL" bench datasets/fence/scene.json -t penumbra-wedge,gbp07 --sweep samples=16,64 $COMMON \
      -s shadow_map_size=1024 -r 256x256 --repeat 5 --out $D/fence
    ;;
  fence-dcs)
    # dcs+STSV ((DCS+STSV)16 and (DCS+STSV)64 of Fig. 8): perforated triangles increment the counters of the
    # samples their STSV hides.
    "$SL" bench datasets/fence/scene.json -t dcs --sweep samples=16,64 $COMMON -r 256x256 --repeat 5 \
      --out $D/fence-dcs
    ;;
  meshed)
    # The "equivalent mesh" (Fig. 11 b): dcs at N = 16 and 64, and penumbra-wedge (N is unused without
    # perforated casters: no sweep), on the canopy meshed along texel boundaries: 11 585 wedges drawn.
    "$SL" bench datasets/fence-meshed/scene.json -t dcs --sweep samples=16,64 $COMMON -r 256x256 --repeat 3 \
      --out $D/meshed
    "$SL" bench datasets/fence-meshed/scene.json -t penumbra-wedge $COMMON -r 256x256 --repeat 3 \
      --out $D/meshed-pwedge
    ;;
  references)
    # Whether the meshed runs may be scored against fence-meshed's own reference: the two references (Embree,
    # 1024 samples, 256x256) against each other, into references.json.
    OUT=$(mktemp -d)
    "$SL" reference datasets/fence/scene.json -n 1024 -r 256x256 -q -o "$OUT/fence"
    "$SL" reference datasets/fence-meshed/scene.json -n 1024 -r 256x256 -q -o "$OUT/fence-meshed"
    "$SL" compare "$OUT/fence-meshed/buffers.vti" "$OUT/fence/buffers.vti" -q -o "$OUT/compare"
    python3 - "$OUT/compare/metrics.json" > $D/references.json <<'PY'
import json, sys
metrics = json.load(open(sys.argv[1]))
metrics["test"] = "reference of datasets/fence-meshed/scene.json (Embree, 1024 samples, 256x256)"
metrics["reference"] = "reference of datasets/fence/scene.json (Embree, 1024 samples, 256x256)"
print(json.dumps(metrics, indent=1))
PY
    rm -rf "$OUT"
    ;;
  coverage)
    # How many rasterised fragments each side needs against how many pixel-volume pairs it must cover (the
    # exact regions): wedges_covering summed over the image (dcs on the mesh) against wedge_fragments, and
    # stsv_covering summed (penumbra-wedge on fence) against stsv_fragments, one 256x256 frame each, N = 16, into
    # coverage.json. The hull's slack is the project's (dcs's wedge hulls, STSVs' screen polygons), not the paper's.
    OUT=$(mktemp -d)
    "$SL" render datasets/fence-meshed/scene.json -t dcs -s samples=16 -r 256x256 -q -o "$OUT/meshed-dcs"
    "$SL" render datasets/fence/scene.json -t penumbra-wedge -s samples=16 -r 256x256 -q -o "$OUT/fence-pwedge"
    python3 - "$OUT" > $D/coverage.json <<'PY'
import json, os, sys
rows = []
for name in ("meshed-dcs", "fence-pwedge"):
    stats = json.load(open(os.path.join(sys.argv[1], name, "stats.json")))
    pixels = stats["resolution"][0] * stats["resolution"][1]
    statistics = stats["technique_statistics"]
    row = {"run": name, "scene": stats["scene"], "technique": stats["technique"], "resolution": stats["resolution"]}
    for buffer, fragments in (("wedges_covering", "wedge_fragments"), ("stsv_covering", "stsv_fragments")):
        if buffer in stats["buffers"]:
            row[buffer + "_sum"] = round(stats["buffers"][buffer]["mean"] * pixels)
            row[fragments] = statistics[fragments]
    rows.append(row)
print(json.dumps(rows, indent=1))
PY
    rm -rf "$OUT"
    ;;
  fence-512)
    # The timings again at 512x512 (fill grows 4x on both sides; whether the ratio holds). Errors are not used.
    "$SL" bench datasets/fence/scene.json -t penumbra-wedge --sweep samples=16,64 $COMMON -r 512x512 --repeat 3 \
      --out $D/fence-512
    ;;
  fence-dcs-512)
    "$SL" bench datasets/fence/scene.json -t dcs --sweep samples=16,64 $COMMON -r 512x512 --repeat 3 \
      --out $D/fence-dcs-512
    ;;
  meshed-512)
    "$SL" bench datasets/fence-meshed/scene.json -t dcs --sweep samples=16,64 $COMMON -r 512x512 --repeat 1 \
      --out $D/meshed-512
    ;;
  rerun)
    # The 256x256 ratio once more, in reverse order (N = 64 first), so that a drift of the shared machine's load
    # shows as a spread between the runs rather than as a bias. RERUN names the output (run2 by default; run3 was
    # made the same way, alone on the machine: see summary.md).
    "$SL" bench datasets/fence-meshed/scene.json -t dcs --sweep samples=64,16 $COMMON -r 256x256 --repeat 3 \
      --out $D/meshed-${RERUN:-run2}
    "$SL" bench datasets/fence/scene.json -t dcs,penumbra-wedge --sweep samples=64,16 $COMMON -r 256x256 \
      --repeat 5 --out $D/fence-${RERUN:-run2}
    ;;
  spread)
    # sqrt(mean v (1 - v)) over each cached reference's penumbra (dcs's script): the penumbra RMSE that N
    # independent uniform samples would reach, the noise floor of the sampled rows.
    python3 docs/bench/dcs/reference_spread.py /tmp/slcache-stsv > $D/reference-spread.json
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
