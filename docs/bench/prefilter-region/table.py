#!/usr/bin/env python3
"""The table of docs/bench/prefilter-region/README.md: per scene and technique, the frame and the prefiltered
structure's build (GPU ms, median of the repeats) before and after, and the RMSE of both.

    python3 docs/bench/prefilter-region/table.py docs/bench/prefilter-region/before docs/bench/prefilter-region/after
"""
import csv
import sys


def rows(directory):
    with open(directory + "/bench.csv") as handle:
        return {(row["scene"].split("/")[-2], row["technique"]): row for row in csv.DictReader(handle)}


def main():
    before, after = rows(sys.argv[1]), rows(sys.argv[2])
    structures = ["moment_map", "power_moment_map", "fourier_basis", "layered_moments"]
    print("| scene | technique | structure | build ms, before → after | frame ms, before → after | RMSE before, after |")
    print("| --- | --- | --- | ---: | ---: | --- |")
    for key, old in before.items():
        new = after[key]
        structure = next(name for name in structures if old.get(name + "_build_gpu_ms"))
        column = structure + "_build_gpu_ms"
        print(f"| {key[0]} | `{key[1]}` | `{structure}` | {float(old[column]):.0f} → {float(new[column]):.0f} "
              f"| {float(old['frame_gpu_ms']):.0f} → {float(new['frame_gpu_ms']):.0f} | {float(old['rmse']):.4f}, "
              f"{float(new['rmse']):.4f} |")


if __name__ == "__main__":
    main()
