// The lesson registry: one line per lesson (src/lessons/Lesson.h says how to add one).
#include "lessons/LessonRegistry.h"

#include "core/Error.h"

namespace sl
{

// Defined in src/lessons/<Name>Lesson.cpp, one file each.
Lesson perspectiveAliasingLesson();
Lesson perspectiveWarpingLesson();
Lesson cascadedShadowMapsLesson();
Lesson acneAndBiasLesson();
Lesson pcfFixedKernelLesson();
Lesson pcssBlockerSearchLesson();
Lesson vsmLightBleedingLesson();
Lesson filterableShadowMapsLesson();
Lesson vssmNonPlanarityLesson();
Lesson backProjectionLesson();
Lesson packetsHierarchyLesson();
Lesson depthComplexityLesson();

const std::vector<Lesson>& lessonRegistry()
{
  static const std::vector<Lesson> registry = {
    perspectiveAliasingLesson(),
    perspectiveWarpingLesson(),
    cascadedShadowMapsLesson(),
    acneAndBiasLesson(),
    pcfFixedKernelLesson(),
    pcssBlockerSearchLesson(),
    vsmLightBleedingLesson(),
    filterableShadowMapsLesson(),
    vssmNonPlanarityLesson(),
    backProjectionLesson(),
    packetsHierarchyLesson(),
    depthComplexityLesson(),
  };
  return registry;
}

const Lesson& findLesson(const std::string& name)
{
  std::string available;
  for (const Lesson& lesson : lessonRegistry())
  {
    if (lesson.name == name)
    {
      return lesson;
    }
    available += (available.empty() ? "" : ", ") + lesson.name;
  }
  throw InputError("--only " + printable(name) + ": no such lesson (lessons: " + available + ")");
}

} // namespace sl
