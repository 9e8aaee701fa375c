#!/usr/bin/env python3
"""The table of docs/bench/minmax-levels/README.md: per scene and technique, the min-max structure's levels built,
its build and the frame (GPU ms of the cold frames, median of the repeats) with every level (`hsm_levels` /
`mssm_levels` = all) and with the levels the frame reads (read), and the RMSE of both.

    python3 docs/bench/minmax-levels/table.py docs/bench/minmax-levels/hsm docs/bench/minmax-levels/mssm
"""
import glob
import json
import sys


def main():
    print("| scene | technique | levels built, all → read | build ms, all → read | frame ms, all → read "
          "| build's share of the frame, all → read | RMSE all, read |")
    print("| --- | --- | --- | ---: | ---: | --- | --- |")
    for directory in sys.argv[1:]:
        pairs = {}
        for path in sorted(glob.glob(directory + "/runs/*.json")):
            run = json.load(open(path))
            levels = next(part.split("=")[1] for part in run["settings"] if "_levels=" in part)
            pairs.setdefault((run["scene"].split("/")[-2], run["technique"]), {})[levels] = run
        for (scene, technique), by in sorted(pairs.items()):
            structure = "dual_mssm" if technique == "yfgl09" else "hierarchical_shadow_map"
            prefix = "mssm" if technique == "yfgl09" else "hsm"
            every, read = by["all"], by["read"]
            # The dual grid is built by the stage hierarchical_shadow_map (vtkSLHsmPass).
            build = [run["stages"]["hierarchical_shadow_map"]["gpu_ms"] for run in (every, read)]
            frame = [run["frame_gpu_ms"] for run in (every, read)]
            top = [int(run["technique_statistics"][prefix + "_top_level"]) for run in (every, read)]
            count = int(read["technique_statistics"][prefix + "_level_count"])
            rmse = [run["error"]["covered"]["rmse"] for run in (every, read)]
            print(f"| {scene} | `{technique}` (`{structure}`) | {top[0]} → {top[1]} of {count} | {build[0]:.0f} → {build[1]:.0f} "
                  f"| {frame[0]:.0f} → {frame[1]:.0f} | {100 * build[0] / frame[0]:.0f} % → {100 * build[1] / frame[1]:.0f} % "
                  f"| {rmse[0]:.4f}, {rmse[1]:.4f} |")


if __name__ == "__main__":
    main()
