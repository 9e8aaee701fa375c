# `reference-sm`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 130
  DESCRIPTOR referenceSmTechnique ReferenceSmTechnique.h
  SOURCES ReferenceSmTechnique.cpp vtkSLReferenceShadowMapPass.cxx
  SHADERS shaders/ReferenceSmAccumulate.glsl shaders/ReferenceSmResolve.glsl
  GPU_TESTS tests/ReferenceSmTest.cpp)
