#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run (docs/testing.md, "Fuzzing and sanitizers"): configures
# build-asan with -DSL_SANITIZE=ON (gcc is fine), builds the test suites and the shadowlab executable, and runs
# the unit and CLI suites, the fuzz-corpus replays and a small GPU subset under the sanitizers. Any report
# fails the run (UB does not recover; ASan aborts on its first error).
#
#   bash scripts/sanitize.sh                # configure, build, run the subset
#
# Environment: BUILD_DIR (default build-asan), JOBS (default: number of cores).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${BUILD_DIR:-build-asan}"
jobs="${JOBS:-$(nproc)}"

# GPU tests that exercise the render path (EGL context, G-buffer, focus reduction, shadow maps, moment maps,
# SAT and HSM structure passes, soft-shadow techniques, read-back) on small scenes: about 20 s together on
# llvmpipe under ASan.
gpu_subset='GpuCpuFocus.*:GpuCpuBias.*:SummedAreaTable.*:HierarchicalShadowMap.GpuLevelsEqualTheCpuBuildExactly'
gpu_subset+=':HardCases.ContactShadowExistsWhereTheBoxTouchesTheGround:Pcss.PointLightGivesTheHardShadow'
gpu_subset+=':MomentTechniques.MatchTheCpuImplementations:Savsm.ExactForAParallelPlanarOccluder'

# -O1 -g1 instead of RelWithDebInfo's -O2 -g: AddressSanitizer's own recommendation (-O1 keeps reports exact), and
# line tables are all its reports need (file:line per frame); the build, most of this script's time, compiles about
# twice as fast (measured per file: ShadowRenderer.cpp 13.0 s -> 6.2 s, ReferenceRenderer.cpp 6.6 s -> 3.1 s).
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSL_SANITIZE=ON >/dev/null
# gpu_sanitize_tests: the six GPU test files the subset below needs (tests/CMakeLists.txt), not all of gpu_tests.
cmake --build "$build_dir" -j "$jobs" --target shadowlab unit_tests cli_tests gpu_sanitize_tests \
  fuzz_replay_scene fuzz_replay_vti fuzz_replay_mesh

# Leak checking is off: Mesa's llvmpipe, EGL and VTK keep allocations alive until exit on purpose (driver
# singletons, VTK's object factories and output window), and every shadowlab process the CLI tests start would
# end with a leak report and exit code 23 instead of its own. What remains on: every out-of-bounds access,
# use after free, double free and undefined behaviour in the project's code; nothing is suppressed.
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# Unit, CLI and fuzz-replay cases through ctest, one process per case and `jobs` at a time (run one binary after
# the other, the CLI suite alone took most of this stage). Not under the sanitizers: the exhaustive shader-contract
# sweep, which preprocesses every variant of every shader (about 15 000 strings, a minute at -O2 already; the
# synthetic ShaderContract cases run the same preprocessor and checks here), and the lesson pages' claims and
# numbers, which regenerate whole lessons (renders and Embree references at 64 px) through the render and reference
# paths the other CLI cases already run under ASan (LessonsCommand's argument handling still runs).
ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" -L '^(unit|cli)$' \
  -E '^(EveryTechnique/ShaderContractOf\.|LessonClaims\.|Lessons/LessonPage\.)'
"$build_dir/tests/gpu_sanitize_tests" --gtest_filter="$gpu_subset"
echo "sanitize.sh: unit, CLI, fuzz replays and GPU subset ($gpu_subset) clean under ASan + UBSan"
