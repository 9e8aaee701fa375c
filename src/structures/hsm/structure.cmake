# `hsm`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 40
  STRUCTURE hierarchicalShadowMapStructure HsmStructure.h
  SOURCES HsmStructure.cpp vtkSLHsmPass.cxx
  SHADERS shaders/HsmBuild.glsl shaders/YsmMssmBuild.glsl
  UNIT_TESTS tests/HsmTopLevelTest.cpp)
