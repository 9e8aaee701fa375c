#!/bin/bash
# How the cost of dcs on an "equivalent mesh" against dcs+STSV on the perforated quad scales with the mesh's
# triangle count (issue 27, src/objectspace/Stsv.md, time ratio). From the repository root:
#   bash docs/bench/stsv-scaling/run.sh [textures] [perforated] [meshed] [table]   (no argument: all)
# - textures: make_textures.py writes square plates of 8^2..256^2 texels with round holes (and 64^2 with 4, 64
#   and 256 holes); mesh_alpha meshes each opaque texel as two triangles, so the mesh has 96..98 304 triangles.
# - perforated / meshed: `bench` of dcs (N = 16 poisson samples, as in docs/bench/stsv) on datasets/fence/scene.json
#   (the canopy is 2 S-triangles with an alpha texture: dcs+STSV) and on datasets/fence-meshed/scene.json (the same
#   texture meshed by mesh_alpha: dcs on plain triangles), sweeping the canopy's texture over the plates and the
#   procedural fence (63 488 triangles). 128x128, --repeat 3 on the mesh (up to 15 s a frame) and 5 on the
#   perforated quad (about 40 ms), so the whole run stays within about 10 minutes on the shared 2-core machine;
#   references are Embree at 64 samples (only to fill bench's error columns). bench's speed-vs-error charts (one
#   point each) are removed to keep the directory small.
# - table: summary.md from the two bench.csv files (technique stage ms and their ratio per texture).
# Timings are llvmpipe's on a loaded 2-core machine: compare ratios within one run, not milliseconds across runs.
set -euo pipefail
D=docs/bench/stsv-scaling
SL=${SHADOWLAB:-build/shadowlab}
PARTS=${*:-textures perforated meshed table}
# alpha_texture paths are relative to the scene file (datasets/<name>/).
T=../../$D
TEXTURES=fence,$T/plate-8-h1.png,$T/plate-16-h2.png,$T/plate-32-h4.png,$T/plate-64-h2.png,$T/plate-64-h8.png
TEXTURES=$TEXTURES,$T/plate-64-h16.png,$T/plate-128-h16.png,$T/plate-256-h32.png
COMMON="-t dcs -s light_samples=poisson -s samples=16 --reference-samples 64 --cache /tmp/slcache-stsv-scaling -r 128x128"
COMMON="$COMMON --scene-sweep /objects/1/alpha_texture=$TEXTURES"

for part in $PARTS; do
  case $part in
  textures) python3 $D/make_textures.py > $D/textures.csv ;;
  perforated)
    "$SL" bench datasets/fence/scene.json $COMMON --repeat 5 --out $D/perforated
    rm -f $D/perforated/speed_vs_error_*.png
    ;;
  meshed)
    "$SL" bench datasets/fence-meshed/scene.json $COMMON --repeat 3 --out $D/meshed
    rm -f $D/meshed/speed_vs_error_*.png
    ;;
  table) python3 $D/table.py $D > $D/summary.md ;;
  *) echo "unknown part $part" >&2; exit 1 ;;
  esac
done
