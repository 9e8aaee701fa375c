# `gbp07`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 90
  DESCRIPTOR gbp07Technique Gbp07Technique.h
  SOURCES Gbp07Technique.cpp vtkSLGbp07Pass.cxx
  SHADERS shaders/Gbp07Visibility.glsl
  GPU_TESTS tests/Gbp07Test.cpp)
