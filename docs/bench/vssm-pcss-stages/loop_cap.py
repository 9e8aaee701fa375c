#!/usr/bin/env python3
"""Which pcss pixels llvmpipe's loop limiter cut short, for the configurations of this bench.

llvmpipe stops a shader invocation's loops once it has run 65535 loop iterations in all
(src/techniques/gbp07/README.md, "`gbp07` and llvmpipe's loop cap"). pcss's brute-force grid runs two nested
loops: the blocker search over w_i and the PCF over w_p, each of at most max_grid_taps^2 taps (the taps themselves
plus one outer iteration per row). Its buffers blocker_samples and pcf_samples hold the taps each pixel planned,
not the taps that ran, so the visibility of a pixel whose planned taps pass the cap is silently wrong (PCF taps
that never ran count as shadowed, and a search cut before its blockers finds none and calls the pixel lit). This
script renders each pcss configuration of the bench with `shadowlab render`, reads buffers.vti and counts, among
the covered pixels:
  - over_cap: blocker_samples + pcf_samples >= 65535 (cut short for certain);
  - near_cap: blocker_samples + pcf_samples + rows >= 65535, with rows = 2 * max_grid_taps + 16 as an upper
    bound of the row iterations and the helpers' small loops (may have been cut short).
Usage (from the repository root; the second argument is the wide grid's max_grid_taps, default 256):
  python3 docs/bench/vssm-pcss-stages/loop_cap.py build/shadowlab [160] > docs/bench/vssm-pcss-stages/loop-cap.md
"""
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import zlib

LOOP_CAP = 65535

# scene, scene overrides, light sizes of the bench (README.md here).
BENCHES = [
    ("datasets/planar-occluder/scene.json", ["/objects/1/size=[1.2,1.2]"], ["0.5", "1", "2", "3", "4"]),
    ("datasets/stacked-occluders/scene.json", [], ["0.5", "1", "2", "3", "4"]),
]
MAP_SIZES = ["512", "2048"]
# loop-cap.md was made with the binary of c897144, when max_grid_taps went up to 256. It now stops at 160
# (two 160^2 grids and their rows stay under the cap): pass 160 to rerun with a current build.
TAPS = ["32", sys.argv[2] if len(sys.argv) > 2 else "256"]


def read_vti_arrays(path, names):
    """The float32 arrays `names` of a VTK XML ImageData file (appended raw, zlib, UInt32 headers)."""
    with open(path, "rb") as file:
        content = file.read()
    start = content.index(b"<AppendedData encoding=\"raw\">")
    data = content[content.index(b"_", start) + 1:]
    arrays = {}
    for name in names:
        match = re.search(rb'Name="' + name.encode() + rb'"[^>]*offset="(\d+)"', content)
        offset = int(match.group(1))
        blocks, _, _ = struct.unpack_from("<III", data, offset)
        sizes = struct.unpack_from("<" + "I" * blocks, data, offset + 12)
        position = offset + 12 + 4 * blocks
        raw = b""
        for size in sizes:
            raw += zlib.decompress(data[position:position + size])
            position += size
        arrays[name] = struct.unpack("<" + "f" * (len(raw) // 4), raw)
    return arrays


def count_cut(shadowlab, scene, overrides, size, map_size, taps, work):
    out = os.path.join(work, "render")
    command = [shadowlab, "render", scene, "-t", "pcss", "-s", "shadow_map_size=" + map_size, "-s",
               "max_grid_taps=" + taps, "-r", "256x256", "-o", out, "--force", "-q"]
    for override in overrides + ["/lights/0/size=" + size]:
        command += ["--scene-set", override]
    subprocess.run(command, check=True)
    arrays = read_vti_arrays(os.path.join(out, "buffers.vti"), ["coverage", "blocker_samples", "pcf_samples"])
    rows = 2 * int(taps) + 16
    covered = over = near = 0
    worst = 0.0
    for coverage, blocker, pcf in zip(arrays["coverage"], arrays["blocker_samples"], arrays["pcf_samples"]):
        if coverage <= 0.5:
            continue
        covered += 1
        worst = max(worst, blocker + pcf)
        over += blocker + pcf >= LOOP_CAP
        near += blocker + pcf + rows >= LOOP_CAP
    return covered, over, near, worst


def main():
    shadowlab = sys.argv[1] if len(sys.argv) > 1 else "build/shadowlab"
    print("| scene | light | shadow_map_size | max_grid_taps | largest planned taps (w_i + w_p) | pixels over the cap | "
          "pixels within 2 max_grid_taps + 16 of it | covered pixels |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as work:
        for scene, overrides, sizes in BENCHES:
            name = os.path.basename(os.path.dirname(scene)) + "".join(" " + o for o in overrides)
            for size in sizes:
                for map_size in MAP_SIZES:
                    for taps in TAPS:
                        covered, over, near, worst = count_cut(shadowlab, scene, overrides, size, map_size, taps, work)
                        print(f"| {name} | {size} | {map_size} | {taps} | {worst:.0f} | {over} | {near} | {covered} |")
                        sys.stdout.flush()


if __name__ == "__main__":
    main()
