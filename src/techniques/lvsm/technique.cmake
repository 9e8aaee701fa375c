# `lvsm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 45
  DESCRIPTOR lvsmTechnique LvsmTechnique.h
  SOURCES LvsmTechnique.cpp vtkSLLvsmPass.cxx
  SHADERS shaders/LvsmVisibility.glsl
  GPU_TESTS tests/LvsmTest.cpp)
