# The techniques, collected from their folders (cmake/PluginFolders.cmake): every src/techniques/<folder>/technique.cmake
# calls sl_technique() once, and from those calls come the techniques area's sources, the technique shaders
# cmake/Shaders.cmake embeds, the test files tests/CMakeLists.txt adds to unit_tests and gpu_tests, and the registry's
# table (a generated .cpp calling every folder's descriptor function). Adding a technique adds a folder and edits no
# file outside it (src/techniques/README.md).
#
# sl_technique(ORDER <integer>                       position in the registry, so in `shadowlab list`
#              DESCRIPTOR <function> <header>         the descriptor function (namespace sl) and the header declaring it
#              SOURCES <files>...                     C++ compiled into sl_techniques
#              [SHADERS <files>...]                   GLSL, embedded as "<folder>/<file name>"
#              [UNIT_TESTS <files>...]                CPU tests, compiled into unit_tests
#              [GPU_TESTS <files>...])                llvmpipe tests, compiled into gpu_tests
# Results, in the registry's order: SL_TECHNIQUE_FOLDERS, SL_TECHNIQUE_SOURCES (with the generated table),
# SL_TECHNIQUE_SHADERS (embedded names) and SL_TECHNIQUE_SHADER_FILE_<embedded name> (its file),
# SL_TECHNIQUE_UNIT_TESTS, SL_TECHNIQUE_GPU_TESTS.
include(${CMAKE_CURRENT_LIST_DIR}/PluginFolders.cmake)

function(sl_technique)
  _sl_plugin_declare(TECHNIQUE technique.cmake DESCRIPTOR ${ARGN})
endfunction()

sl_collect_plugin_folders(TECHNIQUE techniques technique.cmake ${CMAKE_CURRENT_LIST_DIR}/TechniqueTable.cpp.in
  ${CMAKE_CURRENT_BINARY_DIR}/generated/techniques/TechniqueTable.cpp "")
