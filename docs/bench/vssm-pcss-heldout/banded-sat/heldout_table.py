#!/usr/bin/env python3
"""The table of docs/bench/vssm-pcss-heldout/README.md from one bench of pcss and vssm over the held-out scenes:
per scene the map size, both frames (GPU ms, median of the repeats), their ratio, the technique passes' ratio and the
share of vssm's frame its SAT, HSM and shadow map stages take. Usage: heldout_table.py BENCH_DIR (with bench.csv and
bench.json, or the sizes.csv a committed run keeps)."""
import csv
import json
import sys

directory = sys.argv[1]
rows = {}
for row in csv.DictReader(open(f"{directory}/bench.csv")):
    rows[(row["scene"].split("/")[-2], row["technique"])] = row
sizes = {}
try:
    for configuration in json.load(open(f"{directory}/bench.json"))["configurations"]:
        key = (configuration["scene"].split("/")[-2], configuration["technique"])
        sizes[key] = (configuration.get("result") or {}).get("shadow_map_size_chosen", "")
except FileNotFoundError:
    for size in csv.DictReader(open(f"{directory}/sizes.csv")):
        sizes[(size["scene"].split("/")[-2], size["technique"])] = size["shadow_map_size_chosen"]
print("| scene | map | `pcss` frame | `vssm` frame | frame ratio | pass ratio |"
      " `vssm`'s SAT, HSM, shadow map (share of its frame) |")
print("| --- | ---: | ---: | ---: | ---: | ---: | --- |")
for scene in sorted({key[0] for key in rows}):
    pcss = rows[(scene, "pcss")]
    vssm = rows[(scene, "vssm")]
    pcss_frame = float(pcss["frame_gpu_ms"])
    vssm_frame = float(vssm["frame_gpu_ms"])
    pass_ratio = float(pcss["technique_gpu_ms"]) / float(vssm["technique_gpu_ms"])
    shares = ", ".join(f"{100 * float(vssm[stage + '_gpu_ms']) / vssm_frame:.0f} %"
                       for stage in ("summed_area_table", "hierarchical_shadow_map", "shadow_map"))
    print(f"| {scene} | {sizes.get((scene, 'vssm'), '')}² | {pcss_frame:.0f} ms | {vssm_frame:.0f} ms |"
          f" {pcss_frame / vssm_frame:.1f}× | {pass_ratio:.1f}× | {shares} |")
