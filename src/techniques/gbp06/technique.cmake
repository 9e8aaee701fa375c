# `gbp06`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 80
  DESCRIPTOR gbp06Technique Gbp06Technique.h
  SOURCES Gbp06Technique.cpp vtkSLGbp06Pass.cxx
  SHADERS shaders/Gbp06Visibility.glsl
  GPU_TESTS tests/Gbp06Test.cpp)
