# The techniques, collected from their folders: every src/techniques/<folder>/technique.cmake calls sl_technique()
# once, and from those calls come the techniques area's sources, the technique shaders cmake/Shaders.cmake embeds,
# the test files tests/CMakeLists.txt adds to unit_tests and gpu_tests, and the registry's table (a generated .cpp
# calling every folder's descriptor function). Adding a technique adds a folder and edits no file outside it
# (src/techniques/README.md).
#
# sl_technique(ORDER <integer>                       position in the registry, so in `shadowlab list`
#              DESCRIPTOR <function> <header>         the descriptor function (namespace sl) and the header declaring it
#              SOURCES <files>...                     C++ compiled into sl_techniques
#              [SHADERS <files>...]                   GLSL, embedded as "<folder>/<file name>"
#              [UNIT_TESTS <files>...]                CPU tests, compiled into unit_tests
#              [GPU_TESTS <files>...])                llvmpipe tests, compiled into gpu_tests
# Paths are relative to the folder. Results, in the registry's order:
#   SL_TECHNIQUE_FOLDERS, SL_TECHNIQUE_SOURCES (with the generated table), SL_TECHNIQUE_SHADERS (embedded names) and
#   SL_TECHNIQUE_SHADER_FILE_<embedded name> (its file), SL_TECHNIQUE_UNIT_TESTS, SL_TECHNIQUE_GPU_TESTS.

function(sl_technique)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "ORDER" "DESCRIPTOR;SOURCES;SHADERS;UNIT_TESTS;GPU_TESTS")
  set(directory ${CMAKE_CURRENT_LIST_DIR})
  get_filename_component(folder ${directory} NAME)
  set(where "src/techniques/${folder}/technique.cmake")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${where}: unknown arguments to sl_technique: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT arg_ORDER MATCHES "^[0-9]+$")
    message(FATAL_ERROR "${where}: ORDER '${arg_ORDER}' is not a non-negative integer")
  endif()
  list(LENGTH arg_DESCRIPTOR descriptorWords)
  if(NOT descriptorWords EQUAL 2)
    message(FATAL_ERROR "${where}: DESCRIPTOR '${arg_DESCRIPTOR}' is not '<function> <header>'")
  endif()
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "${where}: no SOURCES")
  endif()
  foreach(file IN LISTS arg_SOURCES arg_SHADERS arg_UNIT_TESTS arg_GPU_TESTS)
    if(NOT EXISTS ${directory}/${file})
      message(FATAL_ERROR "${where}: ${file} does not exist")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY SL_TECHNIQUE_FOLDERS ${folder})
  set_property(GLOBAL PROPERTY SL_TECHNIQUE_ORDER_${folder} ${arg_ORDER})
  foreach(kind DESCRIPTOR SOURCES SHADERS UNIT_TESTS GPU_TESTS)
    set_property(GLOBAL PROPERTY SL_TECHNIQUE_${kind}_${folder} ${arg_${kind}})
  endforeach()
endfunction()

# Every folder's file, in a deterministic order (the glob's lexicographic one); CONFIGURE_DEPENDS re-runs the
# configuration when a folder's file appears or goes.
file(GLOB _sl_technique_files CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/techniques/*/technique.cmake)
list(SORT _sl_technique_files)
set_property(GLOBAL PROPERTY SL_TECHNIQUE_FOLDERS "")
foreach(_sl_file IN LISTS _sl_technique_files)
  get_filename_component(_sl_folder_dir ${_sl_file} DIRECTORY)
  get_filename_component(_sl_folder ${_sl_folder_dir} NAME)
  get_property(_sl_before GLOBAL PROPERTY SL_TECHNIQUE_FOLDERS)
  list(LENGTH _sl_before _sl_count_before)
  include(${_sl_file})
  get_property(_sl_after GLOBAL PROPERTY SL_TECHNIQUE_FOLDERS)
  list(LENGTH _sl_after _sl_count_after)
  math(EXPR _sl_calls "${_sl_count_after} - ${_sl_count_before}")
  if(NOT _sl_calls EQUAL 1)
    message(FATAL_ERROR "src/techniques/${_sl_folder}/technique.cmake: calls sl_technique() ${_sl_calls} times, not once")
  endif()
endforeach()

# The registry's order: ORDER, then the folder's name for equal ORDERs (zero-padded, so a string sort is numeric).
get_property(_sl_folders GLOBAL PROPERTY SL_TECHNIQUE_FOLDERS)
set(_sl_keyed "")
foreach(_sl_folder IN LISTS _sl_folders)
  get_property(_sl_order GLOBAL PROPERTY SL_TECHNIQUE_ORDER_${_sl_folder})
  string(LENGTH "${_sl_order}" _sl_digits)
  if(_sl_digits GREATER 9)
    message(FATAL_ERROR "src/techniques/${_sl_folder}/technique.cmake: ORDER ${_sl_order} has more than 9 digits")
  endif()
  math(EXPR _sl_padding "9 - ${_sl_digits}")
  string(REPEAT "0" ${_sl_padding} _sl_zeros)
  list(APPEND _sl_keyed "${_sl_zeros}${_sl_order}|${_sl_folder}")
endforeach()
list(SORT _sl_keyed)

set(SL_TECHNIQUE_FOLDERS "")
set(SL_TECHNIQUE_SOURCES "")
set(SL_TECHNIQUE_SHADERS "")
set(SL_TECHNIQUE_UNIT_TESTS "")
set(SL_TECHNIQUE_GPU_TESTS "")
set(_sl_table_includes "")
set(_sl_table_entries "")
foreach(_sl_entry IN LISTS _sl_keyed)
  string(REGEX REPLACE "^[0-9]+\\|" "" _sl_folder "${_sl_entry}")
  set(_sl_dir ${CMAKE_CURRENT_SOURCE_DIR}/src/techniques/${_sl_folder})
  list(APPEND SL_TECHNIQUE_FOLDERS ${_sl_folder})
  foreach(_sl_kind SOURCES UNIT_TESTS GPU_TESTS)
    get_property(_sl_files GLOBAL PROPERTY SL_TECHNIQUE_${_sl_kind}_${_sl_folder})
    list(TRANSFORM _sl_files PREPEND ${_sl_dir}/)
    list(APPEND SL_TECHNIQUE_${_sl_kind} ${_sl_files})
  endforeach()
  get_property(_sl_files GLOBAL PROPERTY SL_TECHNIQUE_SHADERS_${_sl_folder})
  foreach(_sl_shader IN LISTS _sl_files)
    get_filename_component(_sl_name ${_sl_shader} NAME)
    if(DEFINED SL_TECHNIQUE_SHADER_FILE_${_sl_folder}/${_sl_name})
      message(FATAL_ERROR "src/techniques/${_sl_folder}/technique.cmake: two SHADERS named ${_sl_name}")
    endif()
    list(APPEND SL_TECHNIQUE_SHADERS ${_sl_folder}/${_sl_name})
    set(SL_TECHNIQUE_SHADER_FILE_${_sl_folder}/${_sl_name} ${_sl_dir}/${_sl_shader})
  endforeach()
  get_property(_sl_descriptor GLOBAL PROPERTY SL_TECHNIQUE_DESCRIPTOR_${_sl_folder})
  list(GET _sl_descriptor 0 _sl_function)
  list(GET _sl_descriptor 1 _sl_header)
  get_property(_sl_order GLOBAL PROPERTY SL_TECHNIQUE_ORDER_${_sl_folder})
  string(APPEND _sl_table_includes "#include \"techniques/${_sl_folder}/${_sl_header}\"\n")
  string(APPEND _sl_table_entries "    ${_sl_function}(), // ${_sl_folder}, ORDER ${_sl_order}\n")
endforeach()

configure_file(${CMAKE_CURRENT_LIST_DIR}/TechniqueTable.cpp.in
  ${CMAKE_CURRENT_BINARY_DIR}/generated/techniques/TechniqueTable.cpp @ONLY)
list(APPEND SL_TECHNIQUE_SOURCES ${CMAKE_CURRENT_BINARY_DIR}/generated/techniques/TechniqueTable.cpp)
