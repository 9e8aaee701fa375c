# `vsm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 40
  DESCRIPTOR vsmTechnique VsmTechnique.h
  SOURCES VsmTechnique.cpp
  SHADERS shaders/VsmVisibility.glsl)
