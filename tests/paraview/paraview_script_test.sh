#!/usr/bin/env bash
# The open_in_paraview.py that `render` writes, run by ParaView's pvpython under Xvfb: for a sequential, a diverging
# and a categorical buffer (light_leak holds values on shadow-tested pixels only: the others must show the heat map's
# light grey), its screenshot (one pixel per buffer pixel) must show the heat map's colours
# (compare_screenshot.py). pvpython comes from the unpacked python3-paraview of scripts/bootstrap.sh
# (BUILD_DIR/pvpython-root) or from PATH; without either the test is skipped (exit 77), never passed. The bench's
# script must draw its chart.
#   paraview_script_test.sh SHADOWLAB DATASETS BUILD_DIR
set -euo pipefail
shadowlab="$1"
datasets="$2"
build_dir="$3"
here="$(cd "$(dirname "$0")" && pwd)"
root="$build_dir/pvpython-root"
if [[ -x "$root/usr/bin/pvpython" ]]; then
  pvpython=("$root/usr/bin/pvpython" "$here/run_in_pvpython.py" "$root")
elif command -v pvpython >/dev/null; then
  pvpython=(pvpython)
else
  echo "SKIPPED: no pvpython (scripts/bootstrap.sh test unpacks it into $root)"
  exit 77
fi
if ! command -v xvfb-run >/dev/null; then
  echo "SKIPPED: no xvfb-run"
  exit 77
fi
# One X server for every pvpython run, its number drawn from 900-999 (xvfb-run -a alone starts at 99 for every caller,
# and two tests starting their servers at once can race for the same number; tests/cli/ViewTest.cpp draws from
# 100-899). -noreset: by default Xvfb resets when its last client leaves, and a client connecting meanwhile is
# refused; under load this test failed so ("vtkXOpenGLRenderWindow: bad X server connection", pvpython aborted):
# 5 of 6 runs beside three busy loops without it, 0 of 6 with it.
if [[ -z "${SL_PARAVIEW_TEST_DISPLAY:-}" ]]; then
  exec xvfb-run -a -n $((900 + RANDOM % 100)) -s "-screen 0 640x480x24 -noreset" \
    env SL_PARAVIEW_TEST_DISPLAY=1 bash "$0" "$@"
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"
width=128
height=96
"$shadowlab" render "$datasets/stacked-occluders/scene.json" -t vsm --resolution ${width}x${height} --out out 2>"$work/render.log" ||
  { cat "$work/render.log"; exit 1; }
test -f out/open_in_paraview.py
for buffer in visibility light_leak approximation; do
  "${pvpython[@]}" out/open_in_paraview.py --buffer "$buffer" --no-legend --screenshot "$work/shot_$buffer.png" \
    >"$work/pvpython_$buffer.log" 2>&1 || { cat "$work/pvpython_$buffer.log"; exit 1; }
  "${pvpython[@]}" "$here/compare_screenshot.py" "out/heatmap_$buffer.png" "$work/shot_$buffer.png" $width $height
done
# An unknown buffer: a one-line error naming it, nonzero exit.
if "${pvpython[@]}" out/open_in_paraview.py --buffer no_such_buffer --screenshot "$work/x.png" >"$work/bad.log" 2>&1; then
  echo "FAIL: --buffer no_such_buffer succeeded"
  exit 1
fi
grep -q "no scalar buffer 'no_such_buffer'" "$work/bad.log" || { echo "FAIL: no error naming the buffer"; cat "$work/bad.log"; exit 1; }
# The bench's script: its chart of RMSE against frame time is drawn (not a blank view), and a missing column is named.
"$shadowlab" bench "$datasets/stacked-occluders/scene.json" -t hard,pcf --resolution 48x32 --reference-samples 8 \
  --cache "$work/cache" --out bench 2>"$work/bench_run.log" || { cat "$work/bench_run.log"; exit 1; }
test -f bench/open_in_paraview.py
"${pvpython[@]}" bench/open_in_paraview.py --screenshot "$work/bench_chart.png" >"$work/bench.log" 2>&1 ||
  { cat "$work/bench.log"; exit 1; }
"${pvpython[@]}" "$here/check_chart.py" "$work/bench_chart.png"
if "${pvpython[@]}" bench/open_in_paraview.py --y no_such_column --screenshot "$work/y.png" >"$work/bad.log" 2>&1; then
  echo "FAIL: --y no_such_column succeeded"
  exit 1
fi
grep -q "bench.csv has no column 'no_such_column'" "$work/bad.log" || { echo "FAIL: no error naming the column"; cat "$work/bad.log"; exit 1; }
echo "PASS"
