#!/usr/bin/env python3
"""The tables of docs/bench/fourier-terms/README.md: per scene, convsm's Fourier basis build and whole frame (GPU ms,
median of the repeats), the path the build took (paths.csv) and the RMSE, before and after.
Usage: table.py docs/bench/fourier-terms"""
import csv
import sys

directory = sys.argv[1]
paths = {(row["build"], row["scene"]): row for row in csv.DictReader(open(f"{directory}/paths.csv"))}


def load(build, kind):
    return {row["scene"].split("/")[-2]: row for row in csv.DictReader(open(f"{directory}/{build}/{kind}.csv"))}


for kind in ("heldout", "datasets"):
    before, after = load("before", kind), load("after", kind)
    print(f"\n{kind}:\n")
    print("| scene | map | path before → after | basis build | frame | RMSE before, after |")
    print("| --- | ---: | --- | ---: | ---: | --- |")
    for scene in sorted(before):
        old, new = before[scene], after[scene]
        path = lambda build: "sparse" if paths[(build, scene)]["sparse_blur"] == "1" else "tiles"
        print(f"| {scene} | {paths[('after', scene)]['map']}² | {path('before')} → {path('after')} |"
              f" {float(old['fourier_basis_gpu_ms']):.0f} → {float(new['fourier_basis_gpu_ms']):.0f} ms |"
              f" {float(old['frame_gpu_ms']):.0f} → {float(new['frame_gpu_ms']):.0f} ms |"
              f" {float(old['rmse']):.6f}, {float(new['rmse']):.6f} |")
