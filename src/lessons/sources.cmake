# Lessons generated from real runs (src/lessons/Lesson.h): the builder, the registry, one file per lesson; and the
# montage panels of runs that `shadowlab montage` shares with them.
set(SL_LESSONS_SOURCES
  src/lessons/LessonBuilder.cpp
  src/lessons/LessonRegistry.cpp
  src/lessons/RunMontage.cpp
  src/lessons/PerspectiveAliasingLesson.cpp
  src/lessons/PerspectiveWarpingLesson.cpp
  src/lessons/CascadedShadowMapsLesson.cpp
  src/lessons/AcneAndBiasLesson.cpp
  src/lessons/PcfFixedKernelLesson.cpp
  src/lessons/PcssBlockerSearchLesson.cpp
  src/lessons/VsmLightBleedingLesson.cpp
  src/lessons/FilterableShadowMapsLesson.cpp
  src/lessons/VssmNonPlanarityLesson.cpp
  src/lessons/BackProjectionLesson.cpp
  src/lessons/PacketsHierarchyLesson.cpp
  src/lessons/DepthComplexityLesson.cpp)
