# `yfgl09`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 100
  DESCRIPTOR yfgl09Technique Yfgl09Technique.h
  SOURCES Yfgl09Technique.cpp vtkSLYfgl09Pass.cxx
  SHADERS shaders/Yfgl09Visibility.glsl
  GPU_TESTS tests/Yfgl09Test.cpp)
