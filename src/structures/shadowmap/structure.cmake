# `shadowmap`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 10
  STRUCTURE shadowMapStructure ShadowMapStructure.h
  SOURCES ShadowMapStructure.cpp SamplingErrorBuffers.cpp vtkSLFocusPass.cxx vtkSLLightDepthPass.cxx
  SHADERS shaders/DepthLayerCombine.glsl shaders/ReceiverPolygonId.glsl
  GPU_TESTS tests/DepthLayerTest.cpp tests/AutomaticMapSizeTest.cpp)
