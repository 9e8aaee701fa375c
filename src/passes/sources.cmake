# Stage passes and the GL helpers they share: G-buffer, shading, multi-view (sub-lights). The light-space
# structures' build passes live with their structures (src/lightspace/*/), technique passes in src/techniques.
set(SL_PASSES_SOURCES
  src/passes/PassUtilities.cpp
  src/passes/ScopedRenderTarget.cpp
  src/passes/FullScreenQuad.cpp
  src/passes/ShadowMapRendering.cpp
  src/passes/vtkSLStagePass.cxx
  src/passes/vtkSLGBufferPass.cxx
  src/passes/GpuReceivers.cpp
  src/passes/vtkSLShadingPass.cxx
  src/passes/vtkSLMsaaResolvePass.cxx
  src/passes/vtkSLSubLightAccumulatePass.cxx
  src/passes/vtkSLPartitionAccumulatePass.cxx
  src/passes/vtkSLMultiViewPass.cxx)
