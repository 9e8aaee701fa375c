#!/usr/bin/env python3
"""The survey's Fig. 18 drawn from the bench beside this script (run from the repository root):
    python3 docs/bench/fig18/plot.py docs/bench/fig18/bench.json docs/bench/fig18
writes fig18_<scene>.svg, three panels against the number of maps m (log2 axis), every point the same total texels:
  (a) texel_ratio over the view, max (solid) and mean (dashed), per warp;
  (b) perspective_factor's max over the view, Eq. 1's (1/z)(dz/ds) along the map's t axis, for the maps whose t axis
      runs along the view (warp=lispsm, n = 1e6 or n_opt), beside the closed forms of §4.2-§4.3.1 for a view
      perpendicular to the light (deep-view only; deep-view-behind's light is 15 degrees off the view, where they do
      not apply): m log-split slices with a uniform map each, P (r - 1) / N', with LiSPSM each, P (r - 1) / (sqrt(r) N'),
      and with logarithmic warping each (§4.2.1), P ln(r) / N', r = (z_f / z_n)^(1/m), N' = shadow_map_size - 2 (the
      focus's margin of one texel a side), P = H / 2 cot(fov / 2) pixels per unit, z_n and z_f the tested pixels'
      eye depths;
  (c) misclassified pixels (fraction_above_0.05 of hard's 0/1 against the one-sample reference: the exact ray), in %.
No plotting library: the SVG is written by hand."""
import json
import math
import os
import sys

COLOURS = {"none": "#1f77b4", "lispsm n=1e6": "#ff7f0e", "lispsm n_opt": "#2ca02c"}
CLOSED = {"z-partition, uniform maps": "#9467bd", "z-partition, LiSPSM maps": "#8c564b",
          "z-partition, logarithmic warps": "#d62728"}


def setting(settings, key):
    for item in settings.split():
        if item.startswith(key + "="):
            return item[len(key) + 1:]
    return None


def series_name(settings):
    warp = setting(settings, "warp")
    if warp == "none":
        return "none"
    return "lispsm n=1e6" if float(setting(settings, "warp_n")) > 0 else "lispsm n_opt"


class Panel:
    def __init__(self, svg, left, top, width, height, title, ylabel, values, maps):
        self.svg, self.left, self.top, self.width, self.height = svg, left, top, width, height
        positive = [v for v in values if v > 0]
        self.lo = 10 ** math.floor(math.log10(min(positive)))
        self.hi = 10 ** math.ceil(math.log10(max(positive)))
        self.maxMaps = max(maps)
        svg.append(f'<text x="{left}" y="{top - 10}" font-size="13">{title}</text>')
        svg.append(f'<rect x="{left}" y="{top}" width="{width}" height="{height}" fill="none" stroke="black"/>')
        decade = self.lo
        while decade <= self.hi * 1.0001:
            y = self.y(decade)
            svg.append(f'<line x1="{left}" y1="{y:.1f}" x2="{left + width}" y2="{y:.1f}" stroke="#ddd"/>')
            svg.append(f'<text x="{left - 5}" y="{y + 4:.1f}" text-anchor="end">{decade:g}</text>')
            decade *= 10
        for m in sorted(set(maps)):
            x = self.x(m)
            svg.append(f'<line x1="{x:.1f}" y1="{top}" x2="{x:.1f}" y2="{top + height}" stroke="#ddd"/>')
            svg.append(f'<text x="{x:.1f}" y="{top + height + 15}" text-anchor="middle">{m}</text>')
        svg.append(f'<text x="{left + width / 2}" y="{top + height + 32}" text-anchor="middle">'
                   'maps m (equal total texels)</text>')
        svg.append(f'<text transform="translate({left - 48},{top + height / 2}) rotate(-90)" '
                   f'text-anchor="middle">{ylabel}</text>')

    def x(self, m):
        return self.left + 20 + (self.width - 40) * math.log2(m) / max(1.0, math.log2(self.maxMaps))

    def y(self, v):
        v = max(v, self.lo)
        return self.top + self.height - self.height * math.log(v / self.lo) / math.log(self.hi / self.lo)

    def line(self, points, colour, dashed=False, markers=True):
        path = " ".join(f'{"M" if i == 0 else "L"}{self.x(m):.1f} {self.y(v):.1f}' for i, (m, v) in enumerate(points))
        dash = ' stroke-dasharray="6,4"' if dashed else ""
        self.svg.append(f'<path d="{path}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>')
        if markers:
            for m, v in points:
                self.svg.append(f'<circle cx="{self.x(m):.1f}" cy="{self.y(v):.1f}" r="3" fill="{colour}"/>')


def legend(svg, left, top, entries):
    for i, (name, colour, dashed) in enumerate(entries):
        y = top + 16 * i
        dash = ' stroke-dasharray="6,4"' if dashed else ""
        svg.append(f'<line x1="{left}" y1="{y}" x2="{left + 24}" y2="{y}" stroke="{colour}" stroke-width="2"{dash}/>')
        svg.append(f'<text x="{left + 30}" y="{y + 4}">{name}</text>')


def main():
    bench_file, out_dir = sys.argv[1], sys.argv[2]
    bench = json.load(open(bench_file))
    width, height = (int(v) for v in bench["resolution"].split("x"))
    scenes = {}
    for row in bench["configurations"]:
        if row["status"] != "ok":
            continue
        scene = row["scene"]
        result = row["result"]
        stats = result["view_stats"]
        scenes.setdefault(scene, []).append({
            "series": series_name(row["settings"]), "maps": int(setting(row["settings"], "cascades")),
            "size": int(setting(row["settings"], "shadow_map_size")), "stats": stats,
            "wrong": 100.0 * result["error"]["covered"]["fraction_above_0.05"]})
    for scene, runs in scenes.items():
        name = os.path.basename(os.path.dirname(scene))
        camera = json.load(open(scene))["camera"]
        perpendicular = name == "deep-view"
        pixels_per_unit = 0.5 * height / math.tan(math.radians(camera["view_angle"]) / 2)
        maps = [run["maps"] for run in runs]
        svg = []
        names = sorted({run["series"] for run in runs}, key=list(COLOURS).index)

        ratio = [v for run in runs for v in (run["stats"]["texel_ratio"]["max"], run["stats"]["texel_ratio"]["mean"])]
        a = Panel(svg, 70, 50, 330, 260, "(a) texel_ratio over the view: max (solid), mean (dashed)",
                  "pixels per texel", ratio, maps)
        for series in names:
            points = sorted((r["maps"], r["stats"]["texel_ratio"]) for r in runs if r["series"] == series)
            a.line([(m, s["max"]) for m, s in points], COLOURS[series])
            a.line([(m, s["mean"]) for m, s in points], COLOURS[series], dashed=True)

        warped = [r for r in runs if r["series"] != "none"]
        first = min(warped, key=lambda r: r["maps"])["stats"]["perspective_factor"]
        z_near, z_far = first["depth_min"], first["depth_max"]
        closed = {}
        for m, size in sorted({(r["maps"], r["size"]) for r in runs}):
            ratio_m = (z_far / z_near) ** (1.0 / m)
            scale = pixels_per_unit / (size - 2)
            closed.setdefault("z-partition, uniform maps", []).append((m, scale * (ratio_m - 1)))
            closed.setdefault("z-partition, LiSPSM maps", []).append((m, scale * (ratio_m - 1) / math.sqrt(ratio_m)))
            closed.setdefault("z-partition, logarithmic warps", []).append((m, scale * math.log(ratio_m)))
        values = [r["stats"]["perspective_factor"]["max"] for r in warped]
        values += [v for curve in closed.values() for _, v in curve] if perpendicular else []
        b = Panel(svg, 480, 50, 330, 260, "(b) perspective_factor, max over the view (t along the view)",
                  "pixels per texel", values, maps)
        for series in names:
            if series != "none":
                points = sorted((r["maps"], r["stats"]["perspective_factor"]["max"]) for r in runs
                                if r["series"] == series)
                b.line(points, COLOURS[series])
        if perpendicular:
            for curve, points in closed.items():
                b.line(points, CLOSED[curve], dashed=True, markers=False)

        c = Panel(svg, 890, 50, 330, 260, "(c) misclassified pixels against the exact ray", "% of covered pixels",
                  [r["wrong"] for r in runs], maps)
        for series in names:
            c.line(sorted((r["maps"], r["wrong"]) for r in runs if r["series"] == series), COLOURS[series])

        entries = [(f"warp={s}", COLOURS[s], False) for s in names]
        if perpendicular:
            entries += [(f"closed form: {k}", v, True) for k, v in CLOSED.items()]
        else:
            entries += [("(no closed form: light 15 degrees off the view)", "#ffffff", False)]
        legend(svg, 480, 365, entries)
        header = (f'<svg xmlns="http://www.w3.org/2000/svg" width="1260" height="{380 + 16 * len(entries)}" '
                  'font-family="sans-serif" font-size="11">\n<rect width="100%" height="100%" fill="white"/>\n'
                  f'<text x="70" y="20" font-size="15">{name}: error against the number of maps at equal total texels '
                  f'({bench["resolution"]}, hard)</text>\n')
        with open(os.path.join(out_dir, f"fig18_{name}.svg"), "w") as out:
            out.write(header + "\n".join(svg) + "\n</svg>\n")


if __name__ == "__main__":
    main()
