#!/usr/bin/env python3
"""The per-stage table behind README.md here ("The frame stage by stage, against the paper's 14.8×", from bench.json.

One row per configuration: GPU ms of the frame and of its stages (median of the timed frames, timer
queries), the frame's wall ms, RMSE against the ray tracer, and the frame and technique-pass ratios of each
pcss configuration to vssm at the same light size and map size, with vssm's default subdivision (adaptive,
Alg. 2) and with uniform 8 x 8 sub-kernels.
With --wall, the stages' wall-clock ms instead (each stage ends with glFinish; on llvmpipe the timer queries
miss part of a compute stage's cost, e.g. first touches of freshly allocated textures).
Usage: python3 docs/bench/vssm-pcss-stages/stage_table.py [--wall] docs/bench/vssm-pcss-stages/planar-1.2
"""
import json
import os
import sys

STAGES = ["gbuffer", "focus", "shadow_map", "summed_area_table", "hierarchical_shadow_map", "technique", "shading"]
SHORT = {"gbuffer": "G-buffer", "focus": "focus", "shadow_map": "SM", "summed_area_table": "SAT",
         "hierarchical_shadow_map": "HSM", "technique": "pass", "shading": "shading"}


def light_size(row):
    overrides = row["result"]["scene_overrides"]
    return next(o.split("=")[1] for o in overrides if o.startswith("/lights/0/size="))


def main():
    clock = "wall_ms" if "--wall" in sys.argv else "gpu_ms"
    directory = [argument for argument in sys.argv[1:] if argument != "--wall"][0]
    with open(os.path.join(directory, "bench.json")) as file:
        rows = [row for row in json.load(file)["configurations"] if row["status"] == "ok"]
    vssm = {}
    for row in rows:
        result = row["result"]
        if result["technique"] == "vssm":
            parameters = result["parameters"]
            vssm[(light_size(row), parameters["shadow_map_size"], parameters["shadow_subdivision"])] = result
    print("| light | technique | map | taps / subdivision | frame GPU ms | " +
          " | ".join(SHORT[s] + (" (wall)" if clock == "wall_ms" else "") for s in STAGES) +
          " | frame wall ms | RMSE | frame / vssm adaptive, uniform | pass / vssm adaptive, uniform |")
    print("| ---: | --- | ---: | --- | ---: | " + " | ".join("---:" for _ in STAGES) + " | ---: | ---: | ---: | ---: |")
    for row in rows:
        result = row["result"]
        parameters = result["parameters"]
        size = light_size(row)
        stages = result["stages"]
        cells = [f"{stages[s][clock]:.1f}" if s in stages else "" for s in STAGES]
        variant = (str(int(parameters["max_grid_taps"])) if "max_grid_taps" in parameters
                   else parameters["shadow_subdivision"])
        ratios = ["", ""]
        references = [vssm.get((size, parameters["shadow_map_size"], s)) for s in ("adaptive", "uniform")]
        if result["technique"] == "pcss" and all(references):
            ratios = [", ".join(f"{result['frame_gpu_ms'] / r['frame_gpu_ms']:.1f}" for r in references),
                      ", ".join(f"{stages['technique']['gpu_ms'] / r['stages']['technique']['gpu_ms']:.1f}"
                                for r in references)]
        print(f"| {size} | {result['technique']} | {int(parameters['shadow_map_size'])} | {variant} | "
              f"{result['frame_gpu_ms']:.1f} | " + " | ".join(cells) +
              f" | {result['frame_wall_ms']:.1f} | {result['error']['covered']['rmse']:.4f} | {ratios[0]} | {ratios[1]} |")


if __name__ == "__main__":
    main()
