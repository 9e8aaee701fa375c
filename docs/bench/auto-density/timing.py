#!/usr/bin/env python3
"""The timing table of docs/bench/auto-density/README.md, from one bench that swept shadow_map_size=auto,2048 and
auto_texels_per_pixel=1,2 (so every configuration's frames were timed in the same run, one after the other): per
technique, the median over the datasets of the frame GPU ms at d = 1, d = 2 and at the fixed 2048², and of the
ratios. The two 2048² rows (the parameter does not apply there) show the run-to-run spread.
Usage: timing.py BENCH_DIR"""
import csv
import statistics
import sys
from collections import defaultdict

frames = defaultdict(dict)  # (technique, scene) -> setting -> frame ms
for row in csv.DictReader(open(f"{sys.argv[1]}/bench.csv")):
    if not row["frame_gpu_ms"]:
        continue
    settings = dict(item.split("=", 1) for item in row["settings"].split())
    size = settings["shadow_map_size"]
    density = settings["auto_texels_per_pixel"]
    key = f"auto d={density}" if size == "auto" else f"{size} ({density})"
    frames[(row["technique"], row["scene"].split("/")[-2])][key] = float(row["frame_gpu_ms"])

print("| technique | datasets | frame ms, d = 1 | d = 2 | fixed 2048² | 2048² / d = 2 | 2048² / d = 1 | 2048² rows' spread |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for technique in sorted({key[0] for key in frames}):
    rows = [value for key, value in frames.items() if key[0] == technique and len(value) == 4]
    median = lambda values: statistics.median(values)
    d1 = median([row["auto d=1"] for row in rows])
    d2 = median([row["auto d=2"] for row in rows])
    fixed = median([0.5 * (row["2048 (1)"] + row["2048 (2)"]) for row in rows])
    over2 = median([0.5 * (row["2048 (1)"] + row["2048 (2)"]) / row["auto d=2"] for row in rows])
    over1 = median([0.5 * (row["2048 (1)"] + row["2048 (2)"]) / row["auto d=1"] for row in rows])
    spread = median([abs(row["2048 (1)"] - row["2048 (2)"]) / min(row["2048 (1)"], row["2048 (2)"]) for row in rows])
    print(f"| `{technique}` | {len(rows)} | {d1:.0f} | {d2:.0f} | {fixed:.0f} | {over2:.1f}× | {over1:.1f}× | {100 * spread:.0f} % |")
