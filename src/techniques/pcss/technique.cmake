# `pcss`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 30
  DESCRIPTOR pcssTechnique PcssTechnique.h
  SOURCES PcssTechnique.cpp vtkSLPcssPass.cxx
  SHADERS shaders/PcssVisibility.glsl
  GPU_TESTS tests/PcssTest.cpp)
