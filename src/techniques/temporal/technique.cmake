# `temporal`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 25
  DESCRIPTOR temporalTechnique TemporalTechnique.h
  SOURCES TemporalTechnique.cpp vtkSLTemporalPass.cxx
  SHADERS shaders/TemporalVisibility.glsl
  UNIT_TESTS tests/TemporalHistoryTest.cpp
  GPU_TESTS tests/TemporalTest.cpp)
