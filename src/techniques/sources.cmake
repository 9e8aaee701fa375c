# The techniques area: at its root what several techniques share (the pass base classes, CPU twin support, contour
# back-projection); each technique's own sources come from its folder's technique.cmake (cmake/Techniques.cmake,
# which also generates the registry's table).
include(cmake/Techniques.cmake)
set(SL_TECHNIQUES_SOURCES
  src/techniques/vtkSLTechniquePass.cxx
  src/techniques/Registry.cpp
  src/techniques/ShadowMapParameters.cpp
  src/techniques/ShadowMapReference.cpp
  src/techniques/ProbeSupport.cpp
  src/techniques/ApproximationRules.cpp
  src/techniques/SamplingPatterns.cpp
  src/techniques/SoftShadowSupport.cpp
  src/techniques/MomentReference.cpp
  src/techniques/MomentTechniquePass.cxx
  src/techniques/PcssReference.cpp
  src/techniques/ContourBackprojection.cpp
  src/techniques/ContourReceiver.cpp
  src/techniques/VolumeCountStatus.cpp
  src/techniques/vtkSLShadowVolumePass.cxx
  ${SL_TECHNIQUE_SOURCES})
