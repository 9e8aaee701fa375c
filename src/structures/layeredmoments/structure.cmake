# `layeredmoments`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 82
  STRUCTURE layeredMomentsStructure LayeredMomentsStructure.h
  SOURCES LayeredMomentsStructure.cpp vtkSLLayeredMomentsPass.cxx
  SHADERS shaders/LayeredMomentsBuild.glsl shaders/LayeredMomentsHistogram.glsl shaders/LayeredMomentsLayout.glsl
    shaders/LayeredMomentsSparseBlur.glsl
  GPU_TESTS tests/LayeredMomentRegionGpuTest.cpp)
