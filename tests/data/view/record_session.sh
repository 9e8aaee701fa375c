#!/usr/bin/env bash
# Records tests/data/view/session.log, the event file ViewTest.cpp replays: `shadowlab view --record` on a fresh
# Xvfb, driven by xdotool (apt-get install xvfb xdotool; neither is needed to run the test). Re-record when the
# viewer's layout moves the image (the click lands on image pixel (100, 37), a ground pixel in the box's shadow),
# then bless the screenshots: SHADOWLAB_BLESS=1 build/tests/cli_tests --gtest_filter='ViewCommand.*'.
#
#   bash tests/data/view/record_session.sh [build/shadowlab]
set -euo pipefail
cd "$(dirname "$0")/../../.."
shadowlab="${1:-build/shadowlab}"
work="$(mktemp -d)"
trap 'kill "${viewer:-}" "${server:-}" 2>/dev/null || true; rm -rf "$work"' EXIT

display=":$((200 + RANDOM % 500))"
Xvfb "$display" -screen 0 1600x1200x24 -nolisten tcp &
server=$!
sleep 1
export DISPLAY="$display"
# The same command line as the test's (ViewTest.cpp, viewArguments).
"$shadowlab" view datasets/contact/scene.json --resolution 128x128 --technique pcf --set shadow_map_size=512 \
  --record "$work/session.log" --screenshot-dir "$work/shots" &
viewer=$!
window="$(xdotool search --sync --name 'ShadowLab view')"
xdotool mousemove --window "$window" 20 20 # the pointer in the window gives it the keyboard (no window manager)
step() { xdotool "$@"; sleep 1.5; } # one action at a time: each may render a frame
step key s                   # 001: pcf, the shaded image
step key b                   # visibility
step key s                   # 002: pcf, visibility
step key shift+t             # previous technique: hard
# Image pixel (100, 37) at zoom 2: window x = 8 + 2 * 100 + 1; from the top, y = 952 - 1 - (403 + 2 * 37 + 1)
# (the viewer prints where the image lies: "image pixel (x, y) at window pixel (8 + 2x, 403 + 2y)").
step mousemove --window "$window" 209 473 click 1
step key p key p             # select bias_constant_texels
step key plus                # 0.5 -> 2 texel footprints
step key bracketright        # light size 0.8 -> 1
step key b key b             # kernel_texels, texel_ratio
step key s                   # 003: hard, texel_ratio, probed
step key shift+b key shift+b # back to visibility
step key s                   # 004: hard, visibility, probed
step key h                   # the keys, on stdout and over the probe figure
step key s                   # 005: hard, visibility, the keys shown
step key f                   # scroll the probe figure (hard's two rows all fit: rows 1..2 of 2)
step key q
wait "$viewer"
viewer=
cp "$work/session.log" tests/data/view/session.log
echo "recorded tests/data/view/session.log ($(wc -l < tests/data/view/session.log) lines)"
