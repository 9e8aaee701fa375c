# The light-space structures: one folder per structure (build pass, typed settings, export, binding) and the
# structure registry (above the passes, below the techniques). See structures/LightSpaceStructure.h.
set(SL_STRUCTURES_SOURCES
  src/structures/LightSpaceStructureRegistry.cpp
  src/structures/shadowmap/ShadowMapStructure.cpp
  src/structures/shadowmap/SamplingErrorBuffers.cpp
  src/structures/shadowmap/vtkSLFocusPass.cxx
  src/structures/shadowmap/vtkSLLightDepthPass.cxx
  src/structures/moments/MomentMapStructure.cpp
  src/structures/moments/vtkSLMomentMapPass.cxx
  src/structures/sat/SatStructure.cpp
  src/structures/sat/vtkSLSatPass.cxx
  src/structures/hsm/HsmStructure.cpp
  src/structures/hsm/vtkSLHsmPass.cxx
  src/structures/mssm/DualMssmStructure.cpp
  src/structures/microrect/MicrorectStructure.cpp
  src/structures/microrect/vtkSLMicrorectPass.cxx
  src/structures/lightsamples/LightSampleSetStructure.cpp
  src/structures/lightsamples/vtkSLLightSamplePass.cxx)
