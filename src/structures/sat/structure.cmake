# `sat`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 30
  STRUCTURE summedAreaTableStructure SatStructure.h
  SOURCES SatStructure.cpp vtkSLSatPass.cxx
  SHADERS shaders/SatBuild.glsl
  GPU_TESTS tests/SatBuildTest.cpp)
