# `pcf`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 20
  DESCRIPTOR pcfTechnique PcfTechnique.h
  SOURCES PcfTechnique.cpp vtkSLPcfPass.cxx
  SHADERS shaders/PcfVisibility.glsl)
