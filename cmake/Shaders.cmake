# Embeds every GLSL file into the binary with VTK's vtk_encode_string (no runtime shader paths).
# The C symbol is derived from the embedded name (pcf/PcfVisibility.glsl -> pcf_PcfVisibility), and a generated
# table lets the ShaderLibrary resolve `#include "pcf/PcfVisibility.glsl"` lines by that name.
# The shared files are listed in shaders/shaders.cmake, by path under shaders/ (no glob); each technique's and each
# light-space structure's own come from its folder (cmake/Techniques.cmake, SL_TECHNIQUE_SHADERS; cmake/Structures.cmake,
# SL_STRUCTURE_SHADERS), embedded as "<folder>/<file name>", so a folder's shader keeps the name it had under shaders/.
include("${VTK_DIR}/vtkEncodeString.cmake")
include(${CMAKE_CURRENT_LIST_DIR}/../shaders/shaders.cmake)

set(SL_SHADER_INCLUDE_DIR ${CMAKE_CURRENT_BINARY_DIR}/shaders)
set(SL_SHADER_SOURCES "")
set(_sl_table_includes "")
set(_sl_table_entries "")
foreach(shader IN LISTS SL_SHADER_FILES)
  set(_sl_shader_file_${shader} ${CMAKE_CURRENT_SOURCE_DIR}/shaders/${shader})
endforeach()
foreach(kind TECHNIQUE STRUCTURE)
  foreach(shader IN LISTS SL_${kind}_SHADERS)
    if(DEFINED _sl_shader_file_${shader})
      message(FATAL_ERROR "shader ${shader}: embedded twice (shaders/shaders.cmake, a technique's or a structure's folder)")
    endif()
    set(_sl_shader_file_${shader} ${SL_${kind}_SHADER_FILE_${shader}})
  endforeach()
endforeach()
foreach(shader IN LISTS SL_SHADER_FILES SL_TECHNIQUE_SHADERS SL_STRUCTURE_SHADERS)
  string(REGEX REPLACE "\\.glsl$" "" stem "${shader}")
  string(REPLACE "/" "_" symbol "${stem}")
  get_filename_component(subdir "${shader}" DIRECTORY)
  file(MAKE_DIRECTORY ${SL_SHADER_INCLUDE_DIR}/${subdir})
  set(_saved_binary_dir ${CMAKE_CURRENT_BINARY_DIR})
  vtk_encode_string(
    INPUT ${_sl_shader_file_${shader}}
    NAME ${symbol}
    HEADER_OUTPUT header
    SOURCE_OUTPUT source)
  list(APPEND SL_SHADER_SOURCES ${source})
  get_filename_component(header_name "${header}" NAME)
  string(APPEND _sl_table_includes "#include \"${header_name}\"\n")
  string(APPEND _sl_table_entries "  { \"${shader}\", ${symbol} },\n")
endforeach()
configure_file(${CMAKE_CURRENT_LIST_DIR}/ShaderTable.cxx.in ${SL_SHADER_INCLUDE_DIR}/ShaderTable.cxx @ONLY)
list(APPEND SL_SHADER_SOURCES ${SL_SHADER_INCLUDE_DIR}/ShaderTable.cxx)
