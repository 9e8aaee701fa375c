#!/usr/bin/env python3
"""Eq. 9 of Yang et al. 2009 against this bench's summed visited_nodes, term by term.

Eq. 9 (Yang et al. 2009 §5) counts the shadow-map samples visited for one receiver point, in units of the main
view's texels, and assumes that every sub-light's map covers the main view's region: the S^2 sub-lights' kernels
are each 1/S^2 of the main kernel's area, so their total is the main kernel's. Over an image, two things this
assumption leaves out change the total of the pixel-wise brute force (1 x 1 packets, hierarchy=off, where
visited_nodes is exactly the dual cells of each pixel's kernel):
  - pairs: only (pixel, sub-light) pairs that the lit / umbra test leaves non-trivial visit anything, and a
    sub-light w/S wide has a narrower penumbra than the whole light, so fewer than S^2 times the main light's
    non-trivial pixels are searched: factor pairs_S / (S^2 pairs_1);
  - texels: each sub-light's map is focused for that sub-light (src/techniques/gbp07/README.md, "Multi-view shadow
    maps"): its window is fitted to the receivers seen from its centre and grown by (w/2)/near, so a smaller
    sub-light gets a smaller window and smaller texels, and the same kernel in world units spans more of them.
    Eq. 9 with each sub-light's own texels predicts (1 / S^2) sum_k A_1 / A_k for the cells per searched pair
    times S^2, where A_k is sub-light k's window area at the near plane.
The script renders each sub-light of each S as the scene's light with the pixel-wise settings (the multi-view
pass's split, lightspace/LightSamples.cpp splitIntoSubLights; MultiViewTest asserts that such a frame is its
sub-light's), and reads from stats.json the window (light_view.window), visited_nodes's mean over covered
pixels and packet_class's pixels per category (trivial = lit or umbra). Their totals over the sub-lights must
equal the multi-view bench's visited_nodes sum, which the last column checks.
Usage (from the repository root, after docs/bench/yfgl09-multiview-pixelwise):
  python3 docs/bench/yfgl09-multiview/eq9_terms.py build/shadowlab > docs/bench/yfgl09-multiview/eq9-terms.md
"""
import json
import os
import subprocess
import sys
import tempfile

SCENES = ["planar-occluder", "near-light"]
# The pixel-wise brute force of docs/bench/yfgl09-multiview-pixelwise.
SETTINGS = ["-s", "shadow_map_size=128", "-s", "packet_width=1", "-s", "packet_height=1", "-s", "hierarchy=off",
            "-r", "128x128"]


def render_sub_light(shadowlab, scene, center, size, work):
    """(window area at the near plane, summed visited_nodes, non-trivial pixels) of one frame."""
    out = os.path.join(work, "render")
    subprocess.run([shadowlab, "render", scene, "-t", "yfgl09", *SETTINGS, "--scene-set",
                    "/lights/0/center=" + json.dumps(center), "--scene-set", "/lights/0/size=" + repr(size),
                    "-o", out, "--force", "-q"], check=True)
    with open(os.path.join(out, "stats.json")) as file:
        stats = json.load(file)
    x0, x1, y0, y1 = stats["light_view"]["window"]
    categories = stats["buffers"]["packet_class"]["category_pixels"]
    covered = sum(categories.values())
    searched = covered - categories["trivial (lit or umbra)"] - categories["not tested"]
    return (x1 - x0) * (y1 - y0), stats["buffers"]["visited_nodes"]["mean"] * covered, searched


def sub_light_centres(light, per_side):
    """splitIntoSubLights: centre + right * ((i + 0.5) step - size / 2) + up * ((j + 0.5) step - size / 2)."""
    centre, up, normal, size = light["center"], light["up"], light["normal"], light["size"]
    right = [up[1] * normal[2] - up[2] * normal[1], up[2] * normal[0] - up[0] * normal[2],
             up[0] * normal[1] - up[1] * normal[0]]  # the grid is symmetric, so right's sign does not matter
    step = size / per_side
    for j in range(per_side):
        for i in range(per_side):
            a = (i + 0.5) * step - 0.5 * size
            b = (j + 0.5) * step - 0.5 * size
            yield [centre[c] + right[c] * a + up[c] * b for c in range(3)], step


def measured_sums(bench_dir):
    with open(os.path.join(bench_dir, "bench.json")) as file:
        rows = json.load(file)["configurations"]
    sums = {}
    for row in rows:
        result = row["result"]
        scene = os.path.basename(os.path.dirname(result["scene"]))
        sums[(scene, int(result["parameters"]["sublights"]))] = result["work_counter_sums"]["visited_nodes"]
    return sums


def main():
    shadowlab = sys.argv[1] if len(sys.argv) > 1 else "build/shadowlab"
    sums = measured_sums("docs/bench/yfgl09-multiview-pixelwise")
    print("| scene | S | visited sum / S=1 | pairs: searched / (S^2 x S=1's) | cells per searched pair x S^2 / S=1's | "
          "texels: (1/S^2) sum A_1/A_k | window area A_k min / mean / max (A_1) | sum over single frames / bench sum |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | --- | ---: |")
    with tempfile.TemporaryDirectory() as work:
        for name in SCENES:
            scene = os.path.join("datasets", name, "scene.json")
            with open(scene) as file:
                light = json.load(file)["lights"][0]
            first = None
            for per_side in (1, 2, 4):
                frames = [render_sub_light(shadowlab, scene, c, s, work) for c, s in sub_light_centres(light, per_side)]
                areas = [frame[0] for frame in frames]
                visited = sum(frame[1] for frame in frames)
                searched = sum(frame[2] for frame in frames)
                first = first or (areas[0], visited, searched)
                count = per_side * per_side
                texels = sum(first[0] / a for a in areas) / count
                pairs = searched / (count * first[2])
                cells = (visited / searched) * count / (first[1] / first[2])
                print(f"| {name} | {per_side} | {visited / first[1]:.2f} | {pairs:.2f} | {cells:.2f} | {texels:.2f} | "
                      f"{min(areas):.2f} / {sum(areas) / count:.2f} / {max(areas):.2f} ({first[0]:.2f}) | "
                      f"{visited / sums[(name, per_side)]:.4f} |")
                sys.stdout.flush()


if __name__ == "__main__":
    main()
