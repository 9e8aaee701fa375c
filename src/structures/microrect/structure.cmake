# `microrect`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 60
  STRUCTURE microrectStructure MicrorectStructure.h
  SOURCES MicrorectStructure.cpp vtkSLMicrorectPass.cxx
  SHADERS shaders/MicrorectBuild.glsl)
