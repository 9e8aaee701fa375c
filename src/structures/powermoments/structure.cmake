# `power_moment_map`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 81
  STRUCTURE powerMomentMapStructure PowerMomentMapStructure.h
  SOURCES PowerMomentMapStructure.cpp vtkSLPowerMomentMapPass.cxx
  SHADERS shaders/PowerMomentsFromDepth.glsl shaders/PowerMomentsOfDepth.glsl shaders/PowerMomentsSparseBlur.glsl)
