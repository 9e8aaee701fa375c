# `ss08`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 110
  DESCRIPTOR ss08Technique Ss08Technique.h
  SOURCES Ss08Technique.cpp vtkSLSs08Pass.cxx
  SHADERS shaders/Ss08Search.glsl shaders/Ss08Loq.glsl shaders/Ss08LoqSmoothing.glsl shaders/Ss08Visibility.glsl
  GPU_TESTS tests/Ss08Test.cpp tests/Ss08QualityTest.cpp tests/Ss08MsaaTest.cpp tests/Ss08HeldOutTest.cpp)
