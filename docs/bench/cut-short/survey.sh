#!/bin/bash
# Cut-short survey (issue 13, item 7): the techniques whose value llvmpipe's loop cap can cut short, on every
# square-light dataset with default settings at 128x128; one CSV line each: cut-short pixels against penumbra
# pixels (from stats.json's cut_short_pixels and category_pixels). From the repository root:
#   bash docs/bench/cut-short/survey.sh > docs/bench/cut-short/survey.csv
set -euo pipefail
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "dataset,technique,cut_short_pixels,penumbra_pixels,percent_of_penumbra,technique_gpu_ms"
for d in bunny contact fence grazing near-light planar-occluder stacked-occluders; do
  for t in gbp06 gbp07 yfgl09; do
    "${SHADOWLAB:-build/shadowlab}" render datasets/$d/scene.json -t $t -r 128x128 -q --out "$OUT"/$d-$t > "$OUT"/$d-$t.log 2>&1
    python3 - "$d" "$t" "$OUT" <<'PY'
import json,sys
d,t=sys.argv[1],sys.argv[2]
s=json.load(open(sys.argv[3]+f'/{d}-{t}/stats.json'))
buf='packet_class' if t=='yfgl09' else 'classification'
c=s['buffers'][buf]['category_pixels']
cut=s['technique_statistics'].get('cut_short_pixels',0)
if t=='yfgl09':
    pen=sum(v for k,v in c.items() if k not in ('not tested','trivial (lit or umbra)'))
else:
    pen=c.get('penumbra',0)+c.get('penumbra over the loop budget',0)
tech=[x['gpu_ms'] for x in s['stages'] if x['stage']=='technique'][0]
print(f"{d},{t},{int(cut)},{int(pen)},{100.0*cut/max(pen,1):.2f},{tech:.0f}",flush=True)
PY
  done
done
