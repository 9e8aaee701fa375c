set(SL_LIGHTSPACE_SOURCES
  src/lightspace/CameraView.cpp
  src/lightspace/LightView.cpp
  src/lightspace/LightSamples.cpp
  src/lightspace/ShadowMapMath.cpp
  src/lightspace/HierarchicalShadowMap.cpp
  src/lightspace/LightStructure.cpp
  src/lightspace/sat/SummedAreaTable.cpp)
