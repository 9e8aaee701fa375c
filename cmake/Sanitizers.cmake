# Build options for finding memory errors and undefined behaviour (docs/testing.md, "Fuzzing and sanitizers").
#
# SL_SANITIZE: AddressSanitizer + UndefinedBehaviorSanitizer on every target of this project (the library,
#   the shadowlab executable, the test suites). Included right after project() so that the flags reach every
#   target defined afterwards, and only those: the Debian libraries (VTK, OpenMesh, Embree, Mesa) stay as
#   packaged. -fno-sanitize-recover makes a UB report fail the test instead of printing and going on;
#   -fno-omit-frame-pointer gives full stacks in reports. scripts/sanitize.sh builds this into build-asan.
#
# SL_FUZZ: the libFuzzer targets of tests/fuzz (clang only: -fsanitize=fuzzer). They are built from the
#   reader sources compiled again with fuzzer instrumentation, not from shadowlab_lib, so a fuzz build
#   compiles only what the targets link. scripts/fuzz.sh builds them into build-fuzz and runs one.
option(SL_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(SL_FUZZ "Build the libFuzzer targets of tests/fuzz (needs clang)" OFF)

set(SL_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)

if(SL_SANITIZE)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    message(FATAL_ERROR "SL_SANITIZE needs gcc or clang (got ${CMAKE_CXX_COMPILER_ID})")
  endif()
  add_compile_options(${SL_SANITIZER_FLAGS})
  add_link_options(${SL_SANITIZER_FLAGS})
endif()

if(SL_FUZZ AND NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "SL_FUZZ needs clang's libFuzzer: configure with -DCMAKE_CXX_COMPILER=clang++-14 "
    "-DCMAKE_C_COMPILER=clang-14 (Debian packages clang-14 and libclang-rt-14-dev)")
endif()
