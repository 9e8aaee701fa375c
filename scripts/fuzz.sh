#!/usr/bin/env bash
# The libFuzzer targets of tests/fuzz (docs/testing.md, "Fuzzing and sanitizers"). Needs clang-14 and
# libclang-rt-14-dev (Debian packages); builds only the fuzz targets and the reader sources they link, with
# clang, into build-fuzz (BUILD_DIR to change).
#
#   bash scripts/fuzz.sh run scene 600     # fuzz the scene loader for 600 s (default 60)
#   bash scripts/fuzz.sh run mesh 600 -jobs=2 -workers=2   # extra arguments go to libFuzzer
#   bash scripts/fuzz.sh merge scene       # minimise the committed corpus with what the runs found
#   bash scripts/fuzz.sh replay vti        # run every committed input and regression once
#
# Targets: scene (scene JSON + --scene-set overrides), vti (readVti), mesh (loadMesh: PLY, OBJ, OFF, STL).
# A run mutates a working copy of the corpus (build-fuzz/corpus/<target>), never the committed one; crashing
# inputs go to build-fuzz/crashes/<target>/. `merge` writes the minimised union back to
# tests/fuzz/corpus/<target>. To keep a crash as a regression, copy it to tests/fuzz/regressions/<target>/
# (docs/testing.md says how to name it).
set -euo pipefail

usage()
{
  echo "usage: bash scripts/fuzz.sh run|merge|replay scene|vti|mesh [seconds] [libFuzzer arguments...]" >&2
  exit 2
}
(($# >= 2)) || usage
mode="$1"
target="$2"
shift 2
case "$target" in scene | vti | mesh) ;; *) usage ;; esac
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build-fuzz}"
source_dir="tests/fuzz"

# nice: the fuzz build and the runs share the machine with everyone's builds.
if [[ ! -f "$build_dir/CMakeCache.txt" ]]; then
  nice -n 10 cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSL_FUZZ=ON \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
fi
nice -n 10 cmake --build "$build_dir" --target "fuzz_$target" -j "${JOBS:-2}"
fuzzer="$build_dir/tests/fuzz/fuzz_$target"

# Inputs longer than this are not generated. The scene and mesh formats show every structure within a few KB;
# the larger seeds (deep nesting) live in regressions/, which libFuzzer would cut to this length.
case "$target" in
  scene) max_len=8192 ;;
  vti) max_len=16384 ;;
  mesh) max_len=8192 ;;
esac
# Leaks are not what these runs look for, and VTK keeps one-time allocations (its object factories and output
# window) alive until exit, which LeakSanitizer would report as a crash of the first input.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0}"
options=(-max_len="$max_len" -timeout=10 -rss_limit_mb=2048 -dict="$source_dir/dictionaries/$target.dict"
  -close_fd_mask=1 -print_final_stats=1)

case "$mode" in
  run)
    seconds="${1:-60}"
    [[ $# -gt 0 ]] && shift
    work="$build_dir/corpus/$target"
    crashes="$build_dir/crashes/$target"
    mkdir -p "$work" "$crashes"
    # The committed corpus is read as a second corpus directory: new inputs are written only to $work.
    exec nice -n 10 "$fuzzer" "${options[@]}" -max_total_time="$seconds" -artifact_prefix="$crashes/" "$@" \
      "$work" "$source_dir/corpus/$target"
    ;;
  merge)
    merged="$build_dir/merged/$target"
    rm -rf "$merged"
    mkdir -p "$merged" "$build_dir/corpus/$target"
    nice -n 10 "$fuzzer" "${options[@]}" -merge=1 "$merged" "$source_dir/corpus/$target" "$build_dir/corpus/$target"
    # Replace the committed corpus only after the merge succeeded; libFuzzer names merged inputs by their SHA-1.
    rm -rf "$source_dir/corpus/$target"
    mv "$merged" "$source_dir/corpus/$target"
    echo "fuzz.sh: $source_dir/corpus/$target now holds $(find "$source_dir/corpus/$target" -type f | wc -l) inputs" \
      "($(du -sh "$source_dir/corpus/$target" | cut -f1))"
    ;;
  replay)
    # libFuzzer runs each file argument once; the regressions are expected not to crash any more.
    exec "$fuzzer" "${options[@]}" "$@" "$source_dir/corpus/$target"/* "$source_dir/regressions/$target"/*
    ;;
  *) usage ;;
esac
