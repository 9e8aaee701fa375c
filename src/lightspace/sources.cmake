# Two areas share src/lightspace/ (and its include root):
# - lightspace: the CPU side, light and camera views and the structures' CPU mirrors (below the passes);
# - structures: each light-space structure's folder (build pass, typed settings, export, binding) and the
#   structure registry (above the passes, below the techniques). See lightspace/LightSpaceStructure.h.
set(SL_LIGHTSPACE_SOURCES
  src/lightspace/CameraView.cpp
  src/lightspace/LightView.cpp
  src/lightspace/LightSamples.cpp
  src/lightspace/LightSampleSet.cpp
  src/lightspace/ShadowMapMath.cpp
  src/lightspace/HierarchicalShadowMap.cpp
  src/lightspace/Microrects.cpp
  src/lightspace/sat/SummedAreaTable.cpp)
set(SL_STRUCTURES_SOURCES
  src/lightspace/LightSpaceStructureRegistry.cpp
  src/lightspace/shadowmap/ShadowMapStructure.cpp
  src/lightspace/shadowmap/vtkSLFocusPass.cxx
  src/lightspace/shadowmap/vtkSLLightDepthPass.cxx
  src/lightspace/moments/MomentMapStructure.cpp
  src/lightspace/moments/vtkSLMomentMapPass.cxx
  src/lightspace/sat/SatStructure.cpp
  src/lightspace/sat/vtkSLSatPass.cxx
  src/lightspace/hsm/HsmStructure.cpp
  src/lightspace/hsm/vtkSLHsmPass.cxx
  src/lightspace/mssm/DualMssmStructure.cpp
  src/lightspace/microrect/MicrorectStructure.cpp
  src/lightspace/microrect/vtkSLMicrorectPass.cxx
  src/lightspace/lightsamples/LightSampleSetStructure.cpp
  src/lightspace/lightsamples/vtkSLLightSamplePass.cxx)
