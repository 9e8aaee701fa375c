#!/usr/bin/env python3
"""The "Packets, hierarchy and sub-lights" table of README.md here, from the issue-5 benches (run from the repository
root):
    python3 docs/bench/yfgl09/table.py > docs/bench/yfgl09/table.md
Technique-pass GPU ms of gbp07, 3x3 packets with hierarchy=off ("packets only"), 1x1 packets
("hierarchy only", docs/bench/yfgl09-pixelwise) and the default ("both"); coherent packets of the default
(% of the non-trivial ones); cells whose pixels were cut short say how many."""
import csv


def rows(path):
    return list(csv.DictReader(open(path)))


def key(row):
    return (row["scene"].split("/")[1], row["scene_overrides"].split("=")[-1])


main = rows("docs/bench/yfgl09/bench.csv")
pixelwise = {key(r): r for r in rows("docs/bench/yfgl09-pixelwise/bench.csv")}


def cell(row):
    if row is None or row["status"] != "ok":
        return "failed"
    cut = float(row.get("cut_short_pixels") or 0)
    return f"{float(row['technique_gpu_ms']):.0f}" + (f" ({cut:.0f} px cut short)" if cut > 0 else "")


table = {}
for row in main:
    entry = table.setdefault(key(row), {})
    if row["technique"] == "gbp07":
        entry["gbp07"] = row
    elif "hierarchy=off" in row["settings"]:
        entry["packets"] = row
    else:
        entry["both"] = row
print("| scene | light | gbp07 | packets only | hierarchy only | both | both vs gbp07 | coherent packets |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for (scene, light), entry in table.items():
    gbp07, both = entry.get("gbp07"), entry.get("both")
    ratio = float(gbp07["technique_gpu_ms"]) / float(both["technique_gpu_ms"])
    print(f"| {scene} | {light} | {cell(gbp07)} | {cell(entry.get('packets'))} | {cell(pixelwise.get((scene, light)))} | "
          f"{cell(both)} | {ratio:.1f}× | {float(both['coherent_packet_percent']):.1f} % |")
