# The randomized differential test against the ray tracer (issue 27): `shadowlab differential`, its GPU test slice
# and the sweep in docs/bench/differential.
set(SL_DIFFERENTIAL_SOURCES
  src/differential/Differential.cpp)
