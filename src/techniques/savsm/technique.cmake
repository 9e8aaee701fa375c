# `savsm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 60
  DESCRIPTOR savsmTechnique SavsmTechnique.h
  SOURCES SavsmTechnique.cpp vtkSLSavsmPass.cxx
  SHADERS shaders/SavsmVisibility.glsl
  GPU_TESTS tests/SavsmTest.cpp)
