#!/usr/bin/env python3
"""The paired table of docs/bench/minmax-levels/README.md: the min-max build's GPU ms (minimum and median of 7 cold
frames) by the build before (levels-*) and after (shared-*) the N-buffer levels shared their finer squares, runs
alternated on one machine.

    python3 docs/bench/minmax-levels/paired.py docs/bench/minmax-levels/shared-reads/paired
"""
import glob
import json
import sys


def main():
    rows = {}
    for path in sorted(glob.glob(sys.argv[1] + "/*/runs/*.json")):
        build = path.split("/")[-3].split("-")[0]
        run = json.load(open(path))
        stage = run["stages"]["hierarchical_shadow_map"]
        key = (run["technique"], " ".join(run["settings"]))
        rows.setdefault(key, {}).setdefault(build, []).append(f"{stage['gpu_ms_min']:.0f} / {stage['gpu_ms']:.0f}")
    print("| technique | setting | 4 reads per texel: min / median ms | 9 reads per 2 x 2 texels: min / median ms |")
    print("| --- | --- | --- | --- |")
    for (technique, setting), by in sorted(rows.items()):
        print(f"| `{technique}` | `{setting}` | {', '.join(by['levels'])} | {', '.join(by['shared'])} |")


if __name__ == "__main__":
    main()
