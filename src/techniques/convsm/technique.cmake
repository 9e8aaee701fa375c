# `convsm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 45
  DESCRIPTOR convsmTechnique ConvsmTechnique.h
  SOURCES ConvsmTechnique.cpp
  SHADERS shaders/ConvsmVisibility.glsl
  GPU_TESTS tests/ConvsmTest.cpp)
