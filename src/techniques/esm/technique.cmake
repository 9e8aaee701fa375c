# `esm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 50
  DESCRIPTOR esmTechnique EsmTechnique.h
  SOURCES EsmTechnique.cpp
  SHADERS shaders/EsmVisibility.glsl)
