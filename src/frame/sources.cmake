# The frame's vocabulary: technique descriptors (what the registry holds) and the frame result every consumer reads.
set(SL_FRAME_SOURCES
  src/frame/TechniqueDescriptor.cpp
  src/frame/FrameResult.cpp
  src/frame/ProbeRecord.cpp
  src/frame/MsaaResolve.cpp
  src/frame/Approximations.cpp)
