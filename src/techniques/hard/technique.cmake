# `hard`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 10
  DESCRIPTOR hardTechnique HardTechnique.h
  SOURCES HardTechnique.cpp vtkSLHardShadowPass.cxx
  SHADERS shaders/HardVisibility.glsl)
