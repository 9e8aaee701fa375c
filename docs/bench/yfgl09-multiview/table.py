#!/usr/bin/env python3
"""The multi-view table of docs/bench/yfgl09/README.md (Yang et al. 2009 §5, Eq. 9) from the bench directories'
bench.json.

Per scene, packet size and hierarchy: for S = 1, 2, 4 (S x S sub-lights), the summed visited_nodes (the image
total of the counter, itself summed over sub-lights), the technique pass's and the frame's GPU ms, the shadow
map + MSSM builds' GPU ms (summed over sub-lights), each as a ratio to S = 1, and the coherent packets, cut-short
pixels, RMSE against Embree and median penumbra kernel (texels, first sub-light).
Usage: python3 docs/bench/yfgl09-multiview/table.py docs/bench/yfgl09-multiview docs/bench/yfgl09-multiview-pixelwise
"""
import json
import os
import sys


def main():
    print("| scene | packet | hierarchy | S | visited_nodes sum | × S=1 | pass GPU ms | × S=1 | frame GPU ms | × S=1 | "
          "SM + MSSM ms | coherent packets % | cut short | RMSE | median kernel (texels) |")
    print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for directory in sys.argv[1:]:
        with open(os.path.join(directory, "bench.json")) as file:
            rows = [row for row in json.load(file)["configurations"] if row["status"] == "ok"]
        first = {}
        for row in rows:
            result = row["result"]
            parameters = result["parameters"]
            stages = result["stages"]
            scene = os.path.basename(os.path.dirname(result["scene"]))
            per_side = int(parameters["sublights"])
            key = (scene, parameters["hierarchy"], parameters["packet_width"], parameters["packet_height"])
            visited = result["work_counter_sums"]["visited_nodes"]
            technique = stages["technique"]["gpu_ms"]
            frame = result["frame_gpu_ms"]
            builds = stages["shadow_map"]["gpu_ms"] + stages["hierarchical_shadow_map"]["gpu_ms"]
            if per_side == 1:
                first[key] = (visited, technique, frame)
            base = first[key]
            statistics = result["technique_statistics"]
            print(f"| {scene} | {int(parameters['packet_width'])}×{int(parameters['packet_height'])} | "
                  f"{parameters['hierarchy']} | {per_side} | {visited:.3g} | {visited / base[0]:.2f} | {technique:.1f} | "
                  f"{technique / base[1]:.2f} | {frame:.1f} | {frame / base[2]:.2f} | {builds:.1f} | "
                  f"{statistics['coherent_packet_percent']:.1f} | {statistics['cut_short_pixels']:.0f} | "
                  f"{result['error']['covered']['rmse']:.4f} | {statistics['median_penumbra_kernel_texels']:.1f} |")


if __name__ == "__main__":
    main()
