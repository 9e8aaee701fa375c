# `lightsamples`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 70
  STRUCTURE lightSampleSetStructure LightSampleSetStructure.h
  SOURCES LightSampleSetStructure.cpp vtkSLLightSamplePass.cxx)
