# `msm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 55
  DESCRIPTOR msmTechnique MsmTechnique.h
  SOURCES MsmTechnique.cpp
  SHADERS shaders/MsmVisibility.glsl
  UNIT_TESTS tests/MsmMathTest.cpp
  GPU_TESTS tests/MsmTest.cpp)
