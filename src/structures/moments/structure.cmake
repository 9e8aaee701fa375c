# `moments`: what the build takes from this folder (cmake/Structures.cmake reads every structure.cmake).
sl_structure(
  ORDER 20
  STRUCTURE momentMapStructure MomentMapStructure.h
  SOURCES MomentMapStructure.cpp MomentPrefilter.cpp ReceiverTiles.cpp vtkSLMomentMapPass.cxx
  SHADERS shaders/MomentsFromDepth.glsl shaders/BoxBlur.glsl shaders/ReceiverTiles.glsl shaders/SparseBoxBlur.glsl shaders/SparseMomentsBlur.glsl
    shaders/MomentsOfDepth.glsl
  UNIT_TESTS tests/ReceiverTilesTest.cpp
  GPU_TESTS tests/MomentRegionGpuTest.cpp)
