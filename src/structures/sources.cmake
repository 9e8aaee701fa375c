# The light-space structures area: at its root the structure interface and what every structure shares (build
# dependencies, texture bytes); each structure's own sources come from its folder's structure.cmake
# (cmake/Structures.cmake, which also generates the registry's table in build order). See structures/LightSpaceStructure.h.
include(cmake/Structures.cmake)
set(SL_STRUCTURES_SOURCES
  src/structures/LightSpaceStructure.cpp
  ${SL_STRUCTURE_SOURCES})
