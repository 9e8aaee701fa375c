# Error metrics of a technique against the ray-traced reference (see src/metrics/ErrorMetrics.h) and the
# file-level comparison behind `shadowlab compare` (src/metrics/Comparison.h); a buffer's profile over the eye's
# depth (src/metrics/DepthProfile.h).
set(SL_METRICS_SOURCES
  src/metrics/ErrorMetrics.cpp
  src/metrics/RegressionComparison.cpp
  src/metrics/Comparison.cpp
  src/metrics/DepthProfile.cpp)
