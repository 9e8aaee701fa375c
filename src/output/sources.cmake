# A frame's files under --out: buffers.vti, light_space.vti, heat maps, stats.json (output/OutputWriter.h).
set(SL_OUTPUT_SOURCES
  src/output/OutputWriter.cpp
  src/output/ParaViewScript.cpp)
