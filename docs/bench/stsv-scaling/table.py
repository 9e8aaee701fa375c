#!/usr/bin/env python3
# summary.md of the STSV scaling bench: per canopy texture, the mesh's triangles and wedges (dcs on fence-meshed),
# the technique stage of dcs on the mesh and of dcs+STSV on the perforated quad (ms, bench's median of --repeat),
# and their ratio; then a least-squares fit of log(ratio) against log(triangles).
# Every perforated run does the same work (2 S-triangles, the same STSV fragments whatever the texture), so their
# spread is the machine's load; the "pooled ratio" divides by the median of all of them, which that noise moves less.
import csv, math, os, statistics, sys

d = sys.argv[1]


def rows(name):
    with open(os.path.join(d, name, "bench.csv")) as f:
        return {r["scene_overrides"].split("=", 1)[-1]: r for r in csv.DictReader(f)}


perforated, meshed = rows("perforated"), rows("meshed")
pooled = statistics.median(float(r["technique_gpu_ms"]) for r in perforated.values() if r["status"] == "ok")
fragments = sorted({r["stsv_fragments"] for r in perforated.values()})
print("| texture | mesh triangles | wedges drawn | dcs on the mesh (ms) | dcs+STSV (ms) | ratio | pooled ratio |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
points = []
for key, m in sorted(meshed.items(), key=lambda kv: int(kv[1]["caster_triangles"] or 0)):
    p = perforated.get(key)
    if p is None or m["status"] != "ok" or p["status"] != "ok":
        print(f"| {os.path.basename(key)} | failed | | | | |")
        continue
    # caster_triangles counts every caster; the ground quad's 2 are the same on both sides.
    triangles = int(m["caster_triangles"]) - 2
    mesh_ms, stsv_ms = float(m["technique_gpu_ms"]), float(p["technique_gpu_ms"])
    ratio = mesh_ms / stsv_ms
    points.append((triangles, mesh_ms / pooled))
    print(f"| {os.path.basename(key)} | {triangles} | {m['wedges_drawn']} | {mesh_ms:.1f} | {stsv_ms:.1f} | {ratio:.2f} "
          f"| {mesh_ms / pooled:.2f} |")
print(f"\nPooled: median dcs+STSV technique stage {pooled:.1f} ms over {len(perforated)} textures (STSV fragments "
      f"per frame: {', '.join(fragments)}).")
if len(points) >= 2:
    xs = [math.log(t) for t, _ in points]
    ys = [math.log(r) for _, r in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print(f"\nFit of the pooled ratio: ~ {math.exp(my - slope * mx):.3g} x triangles^{slope:.2f} over {len(points)} "
          "textures.")
