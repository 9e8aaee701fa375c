#!/bin/sh
# Draws misclassified_vs_K.svg from bench.csv: for each scene, the misclassified pixels (the bench's
# fraction_above_0.05: with resolve=threshold the visibility is 0 or 1 and a point or directional light's reference is
# the exact single ray, so every pixel above 0.05 is wrong by 1) as a percentage of K = 1's, against temporal_frames
# on a log2 axis (the scenes' absolute figures differ fivefold; README.md has them).
# Usage: docs/bench/temporal/plot.sh docs/bench/temporal/bench.csv > docs/bench/temporal/misclassified_vs_K.svg
set -eu
awk -F, '
NR == 1 { for (i = 1; i <= NF; ++i) column[$i] = i; next }
$column["technique"] == "temporal" && $column["status"] == "ok" {
  scene = $column["scene"]; sub(/\/scene\.json$/, "", scene); sub(/^.*\//, "", scene); settings = $column["settings"]
  if (!match(settings, /temporal_frames=[0-9]+/)) next
  k = substr(settings, RSTART + 16, RLENGTH - 16) + 0
  value = $column["fraction_above_0.05"]
  if (!(scene in seen)) { seen[scene] = 1; scenes[++sceneCount] = scene }
  if (k == 1) first[scene] = value
  points[scene, ++count[scene]] = k " " value
}
END {
  width = 560; height = 360; left = 70; right = 170; top = 40; bottom = 50
  plotW = width - left - right; plotH = height - top - bottom
  maxK = 64; yMax = 100
  printf "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-family=\"sans-serif\" font-size=\"12\">\n", width, height
  printf "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n"
  printf "<text x=\"%d\" y=\"22\" font-size=\"14\">temporal: misclassified pixels against the exact ray vs K</text>\n", left
  printf "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"black\"/>\n", left, top + plotH, left + plotW, top + plotH
  printf "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"black\"/>\n", left, top, left, top + plotH
  for (k = 1; k <= maxK; k *= 2) {
    x = left + plotW * log(k) / log(maxK)
    printf "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\" stroke=\"#ddd\"/>\n", x, top, x, top + plotH
    printf "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">%d</text>\n", x, top + plotH + 16, k
  }
  for (i = 0; i <= 4; ++i) {
    v = yMax * i / 4; y = top + plotH - plotH * i / 4
    printf "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, y, left + plotW, y
    printf "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%.0f</text>\n", left - 6, y + 4, v
  }
  printf "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">temporal_frames K (log scale)</text>\n", left + plotW / 2, height - 12
  printf "<text transform=\"translate(16,%d) rotate(-90)\" text-anchor=\"middle\">misclassified pixels (%% of K = 1)</text>\n", top + plotH / 2
  split("#1f77b4 #d62728 #2ca02c #9467bd", colours, " ")
  for (s = 1; s <= sceneCount; ++s) {
    scene = scenes[s]; path = ""
    for (i = 1; i <= count[scene]; ++i) {
      split(points[scene, i], p, " ")
      p[2] = first[scene] > 0 ? 100 * p[2] / first[scene] : 0
      x = left + plotW * log(p[1]) / log(maxK); y = top + plotH - plotH * p[2] / yMax
      path = path (i == 1 ? "M" : " L") sprintf("%.1f %.1f", x, y)
      printf "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n", x, y, colours[s]
    }
    printf "<path d=\"%s\" fill=\"none\" stroke=\"%s\" stroke-width=\"2\"/>\n", path, colours[s]
    printf "<text x=\"%d\" y=\"%d\" fill=\"%s\">%s</text>\n", left + plotW + 10, top + 16 * s, colours[s], scene
  }
  printf "</svg>\n"
}' "$1"
