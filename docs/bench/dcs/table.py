#!/usr/bin/env python3
"""The tables of docs/bench/dcs/summary.md from the benches beside this script (run from the repository root):
    python3 docs/bench/dcs/table.py > docs/bench/dcs/tables.md
1. Light-sample patterns (Forest et al. 2009 Fig. 5, §4.1) x N: RMSE and penumbra RMSE against the 1024-sample
   reference, beside what independent uniform samples would give (reference-spread.json).
2. receiver_offset on bunny.
3. Time and RMSE over light sizes beside gbp07, yfgl09 and pcss; dcs's per-step times and counts.
4. Memory: sample_buffer_bytes and paper_sample_buffer_bytes at 256^2 (memory.json) and by formula at 1024^2,
   beside Forest et al. 2009 §5.1 ("64 x 1024^2 x 1bit + 64 x 16bits ~ 8MB").
Times are medians of the timed frames (timer queries, llvmpipe on a shared 2-core machine): compare ratios
within one run."""
import json
import math
import os

ROOT = "docs/bench/dcs"
PATTERNS = ["grid", "stratified", "poisson", "zero_two", "grid_4x4", "stratified_4x4", "poisson_4x4", "zero_two_4x4"]
REFERENCE_SAMPLES = 1024
MIB = 1024.0 * 1024.0


def configurations(directory):
    path = os.path.join(ROOT, directory, "bench.json")
    if not os.path.isfile(path):
        return None
    with open(path) as file:
        return [c for c in json.load(file)["configurations"]]


def scene_name(configuration):
    return configuration["scene"].split("/")[-2]


def light_size(result):
    for override in result.get("scene_overrides", []):
        if override.startswith("/lights/0/size="):
            return float(override.split("=", 1)[1])
    return None


def spread(scene, size=None):
    """sqrt(mean v (1 - v)) over the reference's penumbra (reference_spread.py), or None. The cache holds one
    reference per effective scene, so a swept size equal to the scene's own is stored without an override."""
    path = os.path.join(ROOT, "reference-spread.json")
    if not os.path.isfile(path):
        return None
    with open(f"datasets/{scene}/scene.json") as file:
        own_size = float(json.load(file)["lights"][0]["size"])
    for row in json.load(open(path)):
        overrides = row["scene_overrides"]
        row_size = float(overrides[0].split("=", 1)[1]) if overrides else own_size
        if row["scene"].split("/")[-2] == scene and row_size == (own_size if size is None else size) \
                and row["samples"] == REFERENCE_SAMPLES:
            return row["penumbra_rms_v_1_minus_v"]
    return None


def cell(value, best, digits=4):
    text = f"{value:.{digits}f}"
    return f"**{text}**" if value == best else text


def patterns(directory, title):
    rows = configurations(directory)
    if rows is None:
        return
    for scene in sorted({scene_name(c) for c in rows}):
        results = {(c["result"]["parameters"]["light_samples"], int(c["result"]["parameters"]["samples"])): c["result"]
                   for c in rows if scene_name(c) == scene and c["status"] == "ok"}
        counts = sorted({n for _, n in results})
        first = next(iter(results.values()))
        width, height = first["resolution"]
        offset = first["parameters"]["receiver_offset"]
        print(f"\n{title}: {scene}, {width}×{height}, receiver_offset = {offset:g}, RMSE (all covered pixels) / "
              f"penumbra RMSE ({first['error']['penumbra']['pixels']} px: 0 < reference < 1); bold: the lowest "
              "of its column:\n")
        print("| pattern | " + " | ".join(f"N = {n} RMSE | N = {n} penumbra" for n in counts) + " |")
        print("| --- | " + " | ".join("---: | ---:" for _ in counts) + " |")
        best = {}
        for n in counts:
            best[(n, "covered")] = min(r["error"]["covered"]["rmse"] for (p, m), r in results.items() if m == n)
            best[(n, "penumbra")] = min(r["error"]["penumbra"]["rmse"] for (p, m), r in results.items() if m == n)
        for pattern in PATTERNS:
            cells = []
            for n in counts:
                result = results.get((pattern, n))
                if result is None:
                    cells += ["failed", ""]
                    continue
                cells.append(cell(result["error"]["covered"]["rmse"], best[(n, "covered")]))
                cells.append(cell(result["error"]["penumbra"]["rmse"], best[(n, "penumbra")]))
            print(f"| {pattern} | " + " | ".join(cells) + " |")
        s = spread(scene)
        if s is not None:
            cells = []
            for n in counts:
                cells += ["", f"{s * math.sqrt(1.0 / n + 1.0 / REFERENCE_SAMPLES):.4f}"]
            print("| *i.i.d. uniform (expected)* | " + " | ".join(cells) + " |")
        times = []
        for n in counts:
            values = sorted(r["frame_gpu_ms"] for (p, m), r in results.items() if m == n)
            times.append(f"N = {n}: {values[0]:.0f}–{values[-1]:.0f} ms (median {values[len(values) // 2]:.0f})")
        print(f"\nFrame GPU time over the eight patterns: {'; '.join(times)}.")


def receiver_offset():
    rows = configurations("receiver-offset")
    if rows is None:
        return
    results = {(float(c["result"]["parameters"]["receiver_offset"]), int(c["result"]["parameters"]["samples"])):
               c["result"] for c in rows if c["status"] == "ok"}
    counts = sorted({n for _, n in results})
    offsets = sorted({o for o, _ in results})
    first = next(iter(results.values()))
    print(f"\n### 2. receiver_offset (bunny, {first['resolution'][0]}×{first['resolution'][1]}, "
          f"{first['parameters']['light_samples']})\n")
    print("| receiver_offset | " + " | ".join(f"N = {n} RMSE | N = {n} penumbra | N = {n} max error | "
                                            f"N = {n} px > 0.05" for n in counts) + " |")
    print("| ---: | " + " | ".join("---: | ---: | ---: | ---:" for _ in counts) + " |")
    for offset in offsets:
        cells = []
        for n in counts:
            error = results[(offset, n)]["error"]
            pixels = error["covered"]["pixels"] * error["covered"]["fraction_above_0.05"]
            cells += [f"{error['covered']['rmse']:.4f}", f"{error['penumbra']['rmse']:.4f}",
                      f"{error['covered']['max_abs_error']:.3f}", f"{pixels:.0f}"]
        print(f"| {offset:g} | " + " | ".join(cells) + " |")


def series(configuration):
    settings = configuration["settings"]
    return configuration["technique"] + (f" {settings}" if settings else "")


def light_sizes(directory):
    rows = configurations(directory)
    if rows is None:
        return
    rows = [c for c in rows if c["status"] == "ok"]
    failed = [c for c in configurations(directory) if c["status"] != "ok"]
    scene = scene_name(rows[0])
    first = rows[0]["result"]
    names = []
    for c in rows:
        if series(c) not in names:
            names.append(series(c))
    sizes = sorted({light_size(c["result"]) for c in rows})
    table = {(series(c), light_size(c["result"])): c["result"] for c in rows}
    print(f"\n{scene}, {first['resolution'][0]}×{first['resolution'][1]}, medians of {first['repeat']} frames; "
          "dcs at its default pattern (poisson); the others at their defaults:\n")
    print("Frame GPU ms (technique pass GPU ms in brackets):\n")
    print("| light size | " + " | ".join(names) + " |")
    print("| ---: | " + " | ".join("---:" for _ in names) + " |")
    for size in sizes:
        cells = []
        for name in names:
            r = table.get((name, size))
            cells.append(f"{r['frame_gpu_ms']:.0f} ({r['stages']['technique']['gpu_ms']:.0f})" if r else "failed")
        print(f"| {size:g} | " + " | ".join(cells) + " |")
    print("\nRMSE / penumbra RMSE (bold: the lowest RMSE at that size; cut short: pixels a technique's loop cap "
          "stopped; i.i.d.: the penumbra RMSE N independent uniform samples would give, reference-spread.json):\n")
    print("| light size | penumbra px | " + " | ".join(names) + " | i.i.d. penumbra N = 16 / 64 |")
    print("| ---: | ---: | " + " | ".join("---:" for _ in names) + " | ---: |")
    for size in sizes:
        present = [table[(name, size)] for name in names if (name, size) in table]
        best = min(r["error"]["covered"]["rmse"] for r in present)
        cells = []
        for name in names:
            r = table.get((name, size))
            if r is None:
                cells.append("failed")
                continue
            cut = r["technique_statistics"].get("cut_short_pixels", 0)
            cut_text = f", {cut:.0f} cut short" if cut else ""
            cells.append(f"{cell(r['error']['covered']['rmse'], best)} / {r['error']['penumbra']['rmse']:.4f}{cut_text}")
        s = spread(scene, size)
        iid = " / ".join(f"{s * math.sqrt(1.0 / n + 1.0 / REFERENCE_SAMPLES):.4f}" for n in (16, 64)) if s else ""
        print(f"| {size:g} | {present[0]['error']['penumbra']['pixels']} | " + " | ".join(cells) + f" | {iid} |")
    print("\ndcs's steps (technique_statistics): GPU ms of the centre's shadow volumes, the wedges and the resolve; "
          "wedge fragments; potential silhouette edges (wedges built) against the centre's silhouette edges:\n")
    print("| light size | N | volumes ms | wedges ms | resolve ms | wedges drawn | wedge fragments | fragments / "
          "pixel | potential silhouette edges | silhouette edges (centre) | potential / centre |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for size in sizes:
        for name in names:
            if not name.startswith("dcs"):
                continue
            r = table.get((name, size))
            if r is None:
                continue
            t = r["technique_statistics"]
            pixels = r["resolution"][0] * r["resolution"][1]
            centre = t["silhouette_edges_centre"]
            print(f"| {size:g} | {r['parameters']['samples']} | {t['volumes_gpu_ms']:.1f} | {t['wedges_gpu_ms']:.1f} | "
                  f"{t['resolve_gpu_ms']:.1f} | {t['wedges_drawn']:.0f} | {t['wedge_fragments']:.0f} | "
                  f"{t['wedge_fragments'] / pixels:.1f} | {t['potential_silhouette_edges']:.0f} | {centre:.0f} | "
                  f"{t['potential_silhouette_edges'] / centre:.2f} |")
    for c in failed:
        print(f"\nFailed: {series(c)} {c.get('scene')} {c.get('result', {}).get('scene_overrides', '')}")


def counters_bytes(width, height, n):
    """sample_buffer_bytes: the 8-bit counters, N/4 words plus 3 (centre count and checksum words), and the
    light_sample_mask, ceil(N/32) words, 4 B each, per pixel (vtkSLDcsPass)."""
    return width * height * (n // 4 + 3) * 4 + width * height * math.ceil(n / 32) * 4


def paper_bytes(width, height, n):
    """Forest et al. 2009 §5.1: LS_buffer N x W x H x 1 bit + the precomputed pattern N x 16 bit."""
    return n * width * height // 8 + n * 2


def memory():
    path = os.path.join(ROOT, "memory.json")
    if not os.path.isfile(path):
        return
    rows = json.load(open(path))
    print("\n### 4. Memory\n")
    print("Measured (technique_statistics at 256×256) and by the same formulas at 1024×1024: sample_buffer_bytes = "
          "W H (N/4 + 3) 4 B + W H ceil(N/32) 4 B (8-bit counters and the hidden-sample mask); "
          "paper_sample_buffer_bytes = N W H / 8 B + 2 N B (Forest et al. 2009 §5.1):\n")
    print("| N | 256² sample_buffer_bytes | formula | 256² paper_sample_buffer_bytes | formula | 1024² sample buffers "
          "| of which counters | of which mask | 1024² paper count | ratio |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for row in rows:
        n = row["samples"]
        width, height = row["resolution"]
        ours = counters_bytes(1024, 1024, n)
        theirs = paper_bytes(1024, 1024, n)
        check = lambda measured, formula: "=" if measured == formula else f"≠ {formula}"
        print(f"| {n} | {row['sample_buffer_bytes']:.0f} ({row['sample_buffer_bytes'] / MIB:.2f} MiB) | "
              f"{check(row['sample_buffer_bytes'], counters_bytes(width, height, n))} | "
              f"{row['paper_sample_buffer_bytes']:.0f} ({row['paper_sample_buffer_bytes'] / MIB:.3f} MiB) | "
              f"{check(row['paper_sample_buffer_bytes'], paper_bytes(width, height, n))} | "
              f"{ours / MIB:.1f} MiB | {1024 * 1024 * (n // 4 + 3) * 4 / MIB:.1f} MiB | "
              f"{1024 * 1024 * math.ceil(n / 32) * 4 / MIB:.1f} MiB | {theirs / MIB:.3f} MiB | {ours / theirs:.1f}× |")
    print(f"| 64 (paper, Forest et al. 2009 §5.1) | | | | | | | | ≈ 8 MB ({paper_bytes(1024, 1024, 64)} B) | |")


print("## Tables (generated by docs/bench/dcs/table.py)")
print("\n### 1. Light-sample patterns (Forest et al. 2009 Fig. 5)")
patterns("patterns", "Default settings")
patterns("patterns-offset", "receiver_offset = 1e-5 (the first default)")
patterns("patterns-near-light", "Default settings")
receiver_offset()
print("\n### 3. Light sizes: dcs beside gbp07, yfgl09 and pcss")
light_sizes("light-size-bunny")
light_sizes("light-size-near-light")
memory()
