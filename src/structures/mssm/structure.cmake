# `mssm`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 50
  STRUCTURE dualMssmStructure DualMssmStructure.h
  SOURCES DualMssmStructure.cpp)
