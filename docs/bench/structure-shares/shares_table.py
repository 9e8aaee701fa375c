#!/usr/bin/env python3
"""Issue 33's must-hold 1 over one bench: per technique and scene, the frame (GPU ms, median of the repeats), the
warm frame (light-space structures reused), each light-space structure's build and its share of the frame, and the
ratio of pcss's frame to vssm's. Usage: shares_table.py BENCH_DIR (with bench.csv)."""
import csv
import sys
from collections import defaultdict

directory = sys.argv[1]
rows = list(csv.DictReader(open(f"{directory}/bench.csv")))
structures = [column[: -len("_build_gpu_ms")] for column in rows[0]
              if column.endswith("_build_gpu_ms") and column != "structures_build_gpu_ms"]


def scene_of(row):
    return row["scene"].split("/")[-2]


print("| technique | scenes | frame (ms) | warm frame (ms) | largest structure: share of the frame | scenes above 25 % |")
print("| --- | ---: | --- | --- | --- | ---: |")
by_technique = defaultdict(list)
for row in rows:
    if row["status"] == "ok":
        by_technique[row["technique"]].append(row)
for technique, technique_rows in by_technique.items():
    frames = [float(row["frame_gpu_ms"]) for row in technique_rows]
    warm = [float(row["warm_frame_gpu_ms"]) for row in technique_rows if row.get("warm_frame_gpu_ms")]
    worst = defaultdict(float)
    above = 0
    for row in technique_rows:
        frame = float(row["frame_gpu_ms"])
        shares = {name: float(row[name + "_build_gpu_ms"]) / frame
                  for name in structures if row.get(name + "_build_gpu_ms")}
        for name, share in shares.items():
            worst[name] = max(worst[name], share)
        above += any(share > 0.25 for share in shares.values())
    largest = max(worst.items(), key=lambda item: item[1]) if worst else ("none", 0.0)
    warm_text = f"{min(warm):.0f}–{max(warm):.0f}" if warm else "–"
    print(f"| `{technique}` | {len(technique_rows)} | {min(frames):.0f}–{max(frames):.0f} | {warm_text} |"
          f" {largest[0]}: up to {100 * largest[1]:.0f} % | {above} |")

print()
print("| scene | `pcss` frame | `vssm` frame | ratio | warm `vssm` frame | warm ratio |")
print("| --- | ---: | ---: | ---: | ---: | ---: |")
pairs = defaultdict(dict)
for row in rows:
    if row["status"] == "ok" and row["technique"] in ("pcss", "vssm"):
        pairs[scene_of(row)][row["technique"]] = row
for scene in sorted(pairs):
    if len(pairs[scene]) != 2:
        continue
    pcss = float(pairs[scene]["pcss"]["frame_gpu_ms"])
    vssm = float(pairs[scene]["vssm"]["frame_gpu_ms"])
    warm = float(pairs[scene]["vssm"]["warm_frame_gpu_ms"])
    print(f"| {scene} | {pcss:.0f} | {vssm:.0f} | {pcss / vssm:.1f}× | {warm:.0f} | {pcss / warm:.1f}× |")
