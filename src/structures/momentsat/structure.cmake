# `moment_sat`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 84
  STRUCTURE momentSatStructure MomentSatStructure.h
  SOURCES MomentSatStructure.cpp vtkSLMomentSatPass.cxx
  SHADERS shaders/MomentSatBuild.glsl shaders/MomentSatLookup.glsl
  GPU_TESTS tests/MomentSatTest.cpp)
