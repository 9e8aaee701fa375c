# `vssm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 70
  DESCRIPTOR vssmTechnique VssmTechnique.h
  SOURCES VssmTechnique.cpp vtkSLVssmPass.cxx
  SHADERS shaders/VssmVisibility.glsl
  UNIT_TESTS tests/QuadTreeTest.cpp
  GPU_TESTS tests/VssmTest.cpp)
