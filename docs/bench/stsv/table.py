#!/usr/bin/env python3
"""The tables of docs/bench/stsv/summary.md from the benches beside this script (run from the repository root):
    python3 docs/bench/stsv/table.py > docs/bench/stsv/tables.md
1. Fig. 11 (Forest et al. 2009 §6: STSV on 2 perforated triangles at 90 fps, DCS16 on the 233 358-triangle mesh at 3.3 fps)
   and the 25-35x of the abstract / §1: the mesh (dcs on fence-meshed) against the perforated fence
   (penumbra-wedge = PWedge+STSV, dcs = dcs+STSV), same samples, for the technique stage, the frame, and the
   mesh's wedge step against the STSV step.
2. Figs. 2, 4, 10 as numbers: RMSE against Embree on fence (PWedge+STSV, dcs+STSV, the mesh, gbp07 at 1024^2).
3. Fig. 9's kind: per-step GPU times (volumes, wedges, STSV, resolve) and what each step drew.
Stage and frame times are medians of the timed frames (timer queries); the per-step times and counts in
technique_statistics are the last timed frame's (src/cli/BenchRunCommand.cpp), so the steps need not sum to the
stage's median. llvmpipe on a shared 2-core machine: compare ratios within one run."""
import json
import math
import os

ROOT = "docs/bench/stsv"
REFERENCE_SAMPLES = 1024
PAPER_FIG11_FPS = (90.0, 3.3)  # STSV on 2 perforated triangles, DCS16 on the 233 358-triangle mesh (§6)
PAPER_RANGE = (25, 35)  # abstract / §1
STEPS = ["volumes_gpu_ms", "wedges_gpu_ms", "stsv_gpu_ms", "resolve_gpu_ms"]


def load(directory):
    """{(technique, N or None): result} of a bench's configurations whose status is ok, or None."""
    path = os.path.join(ROOT, directory, "bench.json")
    if not os.path.isfile(path):
        return None
    results = {}
    for c in json.load(open(path))["configurations"]:
        if c["status"] != "ok":
            print(f"\n(failed: {directory} {c['technique']} {c.get('settings', '')})")
            continue
        r = c["result"]
        samples = r["parameters"].get("samples")
        results[(c["technique"], int(samples) if samples is not None else None)] = r
    return results


def technique_ms(r):
    return r["stages"]["technique"]["gpu_ms"]


def step(r, name):
    return r["technique_statistics"].get(name)


def fmt(value, digits=1):
    return "–" if value is None else f"{value:.{digits}f}"


def ratio_table(title, mesh_dir, fence_dirs):
    mesh = load(mesh_dir)
    fence = {}
    for directory in fence_dirs:
        fence.update(load(directory) or {})
    if mesh is None or not fence:
        return
    first = next(iter(mesh.values()))
    print(f"\n{title} (mesh: `{mesh_dir}`, {first['resolution'][0]}×{first['resolution'][1]}, medians of "
          f"{first['repeat']} frames; fence: `{'`, `'.join(fence_dirs)}`, medians of "
          f"{next(iter(fence.values()))['repeat']} frames):\n")
    print("| N | perforated side | mesh: dcs technique ms | fence: technique ms | **technique ratio** | "
          "frame ratio | mesh wedge step ms | fence STSV step ms | **wedges / STSV ratio** | mesh wedge fragments "
          "| STSV fragments | mesh ms / 10⁶ wedge fragments | STSV ms / 10⁶ fragments |")
    print("| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in (16, 64):
        m = mesh.get(("dcs", n))
        if m is None:
            continue
        for technique, label in (("penumbra-wedge", "PWedge+STSV"), ("dcs", "dcs+STSV")):
            f = fence.get((technique, n))
            if f is None:
                continue
            wedges, stsv = step(m, "wedges_gpu_ms"), step(f, "stsv_gpu_ms")
            wf, sf = step(m, "wedge_fragments"), step(f, "stsv_fragments")
            print(f"| {n} | {label} | {technique_ms(m):.0f} | {technique_ms(f):.1f} | "
                  f"**{technique_ms(m) / technique_ms(f):.0f}×** | {m['frame_gpu_ms'] / f['frame_gpu_ms']:.0f}× | "
                  f"{wedges:.0f} | {stsv:.1f} | **{wedges / stsv:.0f}×** | {wf:.0f} | {sf:.0f} | "
                  f"{wedges / wf * 1e6:.0f} | {stsv / sf * 1e6:.0f} |")
    pw_mesh = load("meshed-pwedge") if mesh_dir == "meshed" else None
    if pw_mesh and ("penumbra-wedge", 64) in pw_mesh:
        m = pw_mesh[("penumbra-wedge", 64)]
        for n in (16, 64):
            f = fence.get(("penumbra-wedge", n))
            if f is None:
                continue
            print(f"| {n} | PWedge+STSV against PWedge on the mesh ({technique_ms(m):.0f} ms, "
                  f"{step(m, 'wedges_drawn'):.0f} wedges) | {technique_ms(m):.0f} | {technique_ms(f):.1f} | "
                  f"**{technique_ms(m) / technique_ms(f):.0f}×** | {m['frame_gpu_ms'] / f['frame_gpu_ms']:.0f}× | "
                  f"{step(m, 'wedges_gpu_ms'):.0f} | {step(f, 'stsv_gpu_ms'):.1f} | "
                  f"**{step(m, 'wedges_gpu_ms') / step(f, 'stsv_gpu_ms'):.0f}×** | {step(m, 'wedge_fragments'):.0f} | "
                  f"{step(f, 'stsv_fragments'):.0f} | "
                  f"{step(m, 'wedges_gpu_ms') / step(m, 'wedge_fragments') * 1e6:.0f} | "
                  f"{step(f, 'stsv_gpu_ms') / step(f, 'stsv_fragments') * 1e6:.0f} |")


RUNS = [("256² main", "meshed", ["fence", "fence-dcs"]), ("256² rerun 2", "meshed-run2", ["fence-run2"]),
        ("256² rerun 3", "meshed-run3", ["fence-run3"]), ("512²", "meshed-512", ["fence-512", "fence-dcs-512"])]


def ratio_overview():
    """The technique-stage ratio of every run side by side: how far the shared machine moves it."""
    runs = []
    for name, mesh_dir, fence_dirs in RUNS:
        mesh = load(mesh_dir)
        fence = {}
        for directory in fence_dirs:
            fence.update(load(directory) or {})
        if mesh and fence:
            runs.append((name, mesh, fence))
    if not runs:
        return
    print("\nTechnique-stage ratio, mesh (dcs on fence-meshed) over the perforated fence, every run (the tables "
          "below give each run's times, steps and fragments):\n")
    print("| N | perforated side | " + " | ".join(name for name, _, _ in runs) + " | paper |")
    print("| ---: | --- | " + " | ".join("---:" for _ in runs) + " | ---: |")
    for n in (16, 64):
        for technique, label in (("penumbra-wedge", "PWedge+STSV"), ("dcs", "dcs+STSV")):
            cells = []
            for _, mesh, fence in runs:
                m, f = mesh.get(("dcs", n)), fence.get((technique, n))
                cells.append(f"{technique_ms(m) / technique_ms(f):.0f}×" if m and f else "–")
            paper = (f"{PAPER_FIG11_FPS[0] / PAPER_FIG11_FPS[1]:.0f}× (Fig. 11, DCS16 mesh vs STSV); "
                     f"{PAPER_RANGE[0]}–{PAPER_RANGE[1]}×") if n == 16 else f"{PAPER_RANGE[0]}–{PAPER_RANGE[1]}×"
            print(f"| {n} | {label} | " + " | ".join(cells) + f" | {paper} |")


def coverage():
    """coverage.json: rasterised fragments against the pixel-volume pairs of the exact regions."""
    path = os.path.join(ROOT, "coverage.json")
    if not os.path.isfile(path):
        return
    rows = {row["run"]: row for row in json.load(open(path))}
    mesh, fence = rows.get("meshed-dcs"), rows.get("fence-pwedge")
    if not mesh or not fence:
        return
    exact = mesh["wedges_covering_sum"] / fence["stsv_covering_sum"]
    drawn = mesh["wedge_fragments"] / fence["stsv_fragments"]
    print(f"\nFragments against the exact regions (coverage.json, one 256×256 frame, N = 16): the mesh's wedges "
          f"cover {mesh['wedges_covering_sum']} (pixel, wedge) pairs (`wedges_covering` summed) and rasterise "
          f"{mesh['wedge_fragments']:.0f} fragments ({mesh['wedge_fragments'] / mesh['wedges_covering_sum']:.1f}×, "
          f"dcs's conservative hulls); the STSVs hold {fence['stsv_covering_sum']} (pixel, STSV) pairs "
          f"(`stsv_covering`) and rasterise {fence['stsv_fragments']:.0f} "
          f"({fence['stsv_fragments'] / fence['stsv_covering_sum']:.1f}×). Drawn fragments: {drawn:.0f}× as many "
          f"on the mesh; exact-region pairs: {exact:.0f}×.")


def spread():
    """sqrt(mean v (1 - v)) over the fence reference's penumbra (reference-spread.json), or None."""
    path = os.path.join(ROOT, "reference-spread.json")
    if not os.path.isfile(path):
        return None
    for row in json.load(open(path)):
        if row["scene"].endswith("datasets/fence/scene.json") and not row["scene_overrides"] \
                and row["samples"] == REFERENCE_SAMPLES and row["resolution"] == [256, 256]:
            return row["penumbra_rms_v_1_minus_v"]
    return None


ROWS = [  # label, bench directory, technique, N, paper figure
    ("PWedge+STSV, N = 16", "fence", "penumbra-wedge", 16, "Fig. 4 a (at 16)"),
    ("PWedge+STSV, N = 64", "fence", "penumbra-wedge", 64, "Fig. 4 a, Fig. 8's PWedge+STSV64"),
    ("dcs+STSV, N = 16", "fence-dcs", "dcs", 16, "Fig. 4 b, Fig. 2 b, Fig. 10 b/d"),
    ("dcs+STSV, N = 64", "fence-dcs", "dcs", 64, "Fig. 4 b, Fig. 2 b, Fig. 10 b/d"),
    ("dcs on fence-meshed, N = 16", "meshed", "dcs", 16, "Fig. 11 b"),
    ("dcs on fence-meshed, N = 64", "meshed", "dcs", 64, ""),
    ("penumbra-wedge on fence-meshed", "meshed-pwedge", "penumbra-wedge", 64, ""),
    ("gbp07, 1024² map", "fence", "gbp07", None, "Fig. 2 a, Fig. 10 a/c (SSM 1024²)"),
]


def rmse_table():
    print("\nAgainst Embree (1024 stratified samples, alpha-tested) at 256×256; the meshed rows against "
          "fence-meshed's own reference (references.json: the two references differ by more than 0.05 on "
          "2 pixels). Penumbra: 0 < reference < 1 (ErrorMetrics.h); on `fence` that is most of the ground.\n")
    print("| configuration | paper | RMSE | penumbra RMSE | penumbra px | penumbra MAE | max abs error | "
          "penumbra px > 0.05 | frame ms |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for label, directory, technique, n, paper in ROWS:
        results = load(directory)
        r = (results or {}).get((technique, n))
        if r is None:
            print(f"| {label} | {paper} | not run | | | | | | |")
            continue
        e = r["error"]
        print(f"| {label} | {paper} | {e['covered']['rmse']:.4f} | {e['penumbra']['rmse']:.4f} | "
              f"{e['penumbra']['pixels']} | {e['penumbra']['mae']:.4f} | {e['covered']['max_abs_error']:.3f} | "
              f"{100 * e['penumbra']['fraction_above_0.05']:.1f} % | {r['frame_gpu_ms']:.0f} |")
    s = spread()
    if s is not None:
        cells = ", ".join(f"N = {n}: {s * math.sqrt(1.0 / n + 1.0 / REFERENCE_SAMPLES):.4f}" for n in (16, 64))
        print(f"\nPenumbra RMSE that N independent uniform samples would give against this reference "
              f"(sqrt(mean v(1 − v)) = {s:.4f} over its penumbra, times sqrt(1/N + 1/1024)): {cells}.")


def steps_table(directories):
    print("\nGPU ms per step (volumes: the centre's shadow volumes; wedges: penumbra wedges, on `fence` only the "
          "ground quad's border; STSV: the soft textured shadow volumes; resolve), the technique stage (median), "
          "the light-space structures (gbp07: focus, 1024² shadow map and its MSSM, before its one pass), the "
          "G-buffer and shading stages, and what each step drew:\n")
    print("| scene | configuration | G-buffer | light-space structures | volumes | wedges | STSV | resolve | "
          "technique stage | shading | frame | wedges drawn | wedge fragments | STSVs | STSV fragments |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for directory in directories:
        results = load(directory)
        if not results:
            continue
        for (technique, n), r in sorted(results.items(), key=lambda item: (item[0][0], item[0][1] or 0)):
            scene = r["scene"].split("/")[-2]
            t = r["technique_statistics"]
            stages = r["stages"]
            structures = sum(v["gpu_ms"] for k, v in stages.items()
                             if k not in ("gbuffer", "technique", "shading", "sublight_accumulate"))
            name = f"{technique} N = {n}" if technique != "gbp07" else "gbp07 1024²"
            steps = " | ".join(fmt(t.get(k)) for k in STEPS)
            counts = " | ".join(fmt(t.get(k), 0) for k in ("wedges_drawn", "wedge_fragments", "stsvs",
                                                            "stsv_fragments"))
            print(f"| {scene} (`{directory}`) | {name} | {stages['gbuffer']['gpu_ms']:.1f} | {structures:.1f} | "
                  f"{steps} | {technique_ms(r):.1f} | {stages['shading']['gpu_ms']:.1f} | {r['frame_gpu_ms']:.1f} | "
                  f"{counts} |")


print("## Tables (generated by docs/bench/stsv/table.py)")
print(f"\n### 1. Perforated triangles against the equivalent mesh (Fig. 11: {PAPER_FIG11_FPS[0]:g} / "
      f"{PAPER_FIG11_FPS[1]:g} fps = {PAPER_FIG11_FPS[0] / PAPER_FIG11_FPS[1]:.1f}×; abstract / §1: "
      f"{PAPER_RANGE[0]}–{PAPER_RANGE[1]}×)")
ratio_overview()
ratio_table("256×256, main parts (fence, fence-dcs, meshed)", "meshed", ["fence", "fence-dcs"])
coverage()
ratio_table("256×256, rerun 2 (sweep order reversed; a ctest -j2 of another session overlapped)", "meshed-run2",
            ["fence-run2"])
ratio_table("256×256, rerun 3 (as rerun 2)", "meshed-run3", ["fence-run3"])
ratio_table("512×512", "meshed-512", ["fence-512", "fence-dcs-512"])
print("\n### 2. RMSE against the ray tracer on `fence` (Figs. 2, 4, 10 as numbers)")
rmse_table()
print("\n### 3. Per-step times (Fig. 9's kind)")
steps_table(["fence", "fence-dcs", "meshed", "meshed-pwedge", "fence-512", "fence-dcs-512", "meshed-512"])
