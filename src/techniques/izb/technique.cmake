# `izb`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 145
  DESCRIPTOR izbTechnique IzbTechnique.h
  SOURCES IzbTechnique.cpp IzbTwin.cpp vtkSLIzbPass.cxx
  SHADERS shaders/IzbCommon.glsl shaders/IzbBin.glsl shaders/IzbTest.glsl shaders/IzbResolve.glsl
  UNIT_TESTS tests/IzbTwinTest.cpp
  GPU_TESTS tests/IzbTest.cpp)
