# `dcs`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
# Its wedge vertex shader, wedge light uniforms and sample counters (shaders/dcs/) are shared with penumbra-wedge
# and the STSV drawer (src/objectspace).
sl_technique(
  ORDER 150
  DESCRIPTOR dcsTechnique DcsTechnique.h
  SOURCES DcsReference.cpp DcsTechnique.cpp vtkSLDcsPass.cxx
  SHADERS shaders/DcsWedgeUpdate.glsl shaders/DcsResolve.glsl
  UNIT_TESTS tests/DcsRuleTest.cpp
  GPU_TESTS tests/DcsTest.cpp)
