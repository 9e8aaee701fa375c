set(SL_PASSES_SOURCES
  src/passes/PassUtilities.cpp
  src/passes/vtkSLStagePass.cxx
  src/passes/vtkSLGBufferPass.cxx
  src/passes/vtkSLLightDepthPass.cxx
  src/passes/vtkSLTechniquePass.cxx
  src/passes/vtkSLShadingPass.cxx
  src/passes/ShadowRenderer.cpp)
