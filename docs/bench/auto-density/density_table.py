#!/usr/bin/env python3
"""The error table of docs/bench/auto-density/README.md: per technique, configurations whose RMSE is worse than the
fixed default's (the bench's --baseline rule) and the sizes chosen, at each auto_texels_per_pixel. Frame times are
not compared here: the runs were timed at different times under different loads (timing.py pairs them in one run).
Usage: density_table.py BASELINE_DIR NAME=BENCH_DIR[+BENCH_DIR ...] [NAME=...]
A column NAME=A+B joins runs of different datasets: B's rows replace A's for the same technique and dataset (the
defaults column: d2's area lights with hard/'s point and directional lights)."""
import csv
import json
import sys
from collections import Counter, defaultdict


def load(directory):
    rows = {}
    for row in csv.DictReader(open(f"{directory}/bench.csv")):
        if row["frame_gpu_ms"]:
            rows[(row["technique"], row["scene"].split("/")[-2])] = row
    try:
        # The size each frame rendered at is in bench.json's results (bench.csv has no column for it).
        for configuration in json.load(open(f"{directory}/bench.json"))["configurations"]:
            key = (configuration["technique"], configuration["scene"].split("/")[-2])
            if key in rows:
                rows[key]["shadow_map_size_chosen"] = str((configuration.get("result") or {}).get("shadow_map_size_chosen", ""))
    except FileNotFoundError:
        # A committed run keeps only sizes.csv (technique, scene, shadow_map_size_chosen) of its bench.json.
        for size in csv.DictReader(open(f"{directory}/sizes.csv")):
            key = (size["technique"], size["scene"].split("/")[-2])
            if key in rows:
                rows[key]["shadow_map_size_chosen"] = size["shadow_map_size_chosen"]
    return rows


def worse(rmse, baseline):
    # bench --baseline's rule (cli/BenchBaseline.h): more than 1e-4 absolute and 1 % relative.
    return rmse - baseline > 1e-4 and rmse - baseline > 0.01 * baseline


def load_joined(directories):
    rows = {}
    for directory in directories.split("+"):
        rows.update(load(directory))
    return rows


baseline = load(sys.argv[1])
runs = [(arg.split("=", 1)[0], load_joined(arg.split("=", 1)[1])) for arg in sys.argv[2:]]
# The techniques of the last run (the density sweep covers the shadow-map techniques whose size it changes).
techniques = sorted({key[0] for key in runs[-1][1]})
header = "| technique | " + " | ".join(f"{name}: worse / compared (where), sizes chosen" for name, _ in runs) + " |"
print(header)
print("| --- |" + " --- |" * len(runs))
totals = defaultdict(lambda: [0, 0])
for technique in techniques:
    cells = []
    for name, rows in runs:
        keys = [key for key in rows if key[0] == technique]
        compared = [key for key in keys if key in baseline and rows[key]["rmse"] and baseline[key]["rmse"]]
        bad = [key for key in compared if worse(float(rows[key]["rmse"]), float(baseline[key]["rmse"]))]
        totals[name][0] += len(bad)
        totals[name][1] += len(compared)
        sizes = Counter(rows[key].get("shadow_map_size_chosen", "") for key in keys)
        size_text = ", ".join((f"{size}²" if size else "size not recorded") + f"×{count}"
                              for size, count in sorted(sizes.items(), key=lambda item: int(item[0] or 0)))
        bad_text = f"{len(bad)} / {len(compared)}" + (f" ({', '.join(key[1] for key in bad)})" if bad else "")
        cells.append(f"{bad_text}; {size_text}")
    print(f"| `{technique}` | " + " | ".join(cells) + " |")
print("| all | " + " | ".join(f"**{totals[name][0]} / {totals[name][1]}**" for name, _ in runs) + " |")
