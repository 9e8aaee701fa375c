# `msmsoft`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 62
  DESCRIPTOR msmSoftTechnique MsmSoftTechnique.h
  SOURCES MsmSoftTechnique.cpp vtkSLMsmSoftPass.cxx
  SHADERS shaders/MsmSoftVisibility.glsl
  UNIT_TESTS tests/MsmSoftMathTest.cpp
  GPU_TESTS tests/MsmSoftTest.cpp)
