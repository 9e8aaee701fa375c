# `shadow-volume`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
# Its GLSL is the shared vtkSLShadowVolumePass's (shaders/shadowvolume/), which dcs and penumbra-wedge derive from.
sl_technique(
  ORDER 140
  DESCRIPTOR shadowVolumeTechnique ShadowVolumeTechnique.h
  SOURCES ShadowVolumeTechnique.cpp
  GPU_TESTS tests/ShadowVolumeTest.cpp)
