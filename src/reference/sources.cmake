set(SL_REFERENCE_SOURCES
  src/reference/EmbreeScene.cpp
  src/reference/LightSampler.cpp
  src/reference/ReferenceRenderer.cpp)
