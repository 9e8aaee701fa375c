# ctest Datasets.GeneratedScenesAreCommitted: runs the generator into SCRATCH and compares every scene.json it writes,
# byte for byte, with the committed one under DATASETS. Run as
#   cmake -DGENERATOR=<exe> -DDATASETS=<repo>/datasets -DSCRATCH=<empty dir> -P CheckCommitted.cmake
file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}")
execute_process(COMMAND "${GENERATOR}" "${SCRATCH}" RESULT_VARIABLE status ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} ${SCRATCH} failed (${status}): ${errors}")
endif()
file(GLOB written RELATIVE "${SCRATCH}" "${SCRATCH}/*/scene.json")
list(LENGTH written count)
if(count EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} wrote no scene.json under ${SCRATCH}")
endif()
foreach(scene IN LISTS written)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${SCRATCH}/${scene}" "${DATASETS}/${scene}"
    RESULT_VARIABLE different)
  if(different)
    message(FATAL_ERROR "datasets/${scene} is not what the generator writes (${SCRATCH}/${scene}); "
      "regenerate with: build/tests/generate_sampling_datasets datasets")
  endif()
  message(STATUS "datasets/${scene}: as generated")
endforeach()
