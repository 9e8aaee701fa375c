# The CPU side of light space: light and camera views and the structures' CPU mirrors (below the passes; each
# structure's build pass, settings and binding are in src/structures/).
set(SL_LIGHTSPACE_SOURCES
  src/lightspace/CameraView.cpp
  src/lightspace/LightView.cpp
  src/lightspace/LayeredMoments.cpp
  src/lightspace/LightSamples.cpp
  src/lightspace/LightSampleSet.cpp
  src/lightspace/ShadowMapMath.cpp
  src/lightspace/AutomaticMapSize.cpp
  src/lightspace/PerspectiveWarp.cpp
  src/lightspace/Cascades.cpp
  src/lightspace/PartitionViews.cpp
  src/lightspace/FittedVirtualShadowMap.cpp
  src/lightspace/CubeFaces.cpp
  src/lightspace/HierarchicalShadowMap.cpp
  src/lightspace/Microrects.cpp
  src/lightspace/SummedAreaTable.cpp
  src/lightspace/MomentHamburger.cpp
  src/lightspace/MomentSummedAreaTable.cpp)
