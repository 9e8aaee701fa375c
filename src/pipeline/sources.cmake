# The pipeline: builds a technique's stages from its descriptor and renders one frame (ShadowRenderer).
set(SL_PIPELINE_SOURCES
  src/pipeline/ShadowRenderer.cpp
  src/pipeline/StructureReuse.cpp)
