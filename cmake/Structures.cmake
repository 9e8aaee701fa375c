# The light-space structures, collected from their folders (cmake/PluginFolders.cmake): every
# src/structures/<folder>/structure.cmake calls sl_structure() once, and from those calls come the structures area's
# sources, the build shaders cmake/Shaders.cmake embeds, the test files tests/CMakeLists.txt adds to unit_tests and
# gpu_tests, and the registry's table in build order. Adding a structure adds a folder and edits no file outside it
# (src/structures/README.md).
#
# sl_structure(ORDER <integer>                       build order: after every structure it is built from
#              STRUCTURE <function> <header>          the function (namespace sl) returning its LightSpaceStructure
#              SOURCES <files>...                     C++ compiled into sl_structures
#              [SHADERS <files>...]                   GLSL, embedded as "<folder>/<file name>"
#              [UNIT_TESTS <files>...]                CPU tests, compiled into unit_tests
#              [GPU_TESTS <files>...])                llvmpipe tests, compiled into gpu_tests
# Results, in build order: SL_STRUCTURE_FOLDERS, SL_STRUCTURE_SOURCES (with the generated table), SL_STRUCTURE_SHADERS
# and SL_STRUCTURE_SHADER_FILE_<embedded name>, SL_STRUCTURE_UNIT_TESTS, SL_STRUCTURE_GPU_TESTS.
include(${CMAKE_CURRENT_LIST_DIR}/PluginFolders.cmake)

function(sl_structure)
  _sl_plugin_declare(STRUCTURE structure.cmake STRUCTURE ${ARGN})
endfunction()

sl_collect_plugin_folders(STRUCTURE structures structure.cmake ${CMAKE_CURRENT_LIST_DIR}/StructureTable.cpp.in
  ${CMAKE_CURRENT_BINARY_DIR}/generated/structures/StructureTable.cpp "&")
