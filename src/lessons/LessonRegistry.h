// Every lesson, in the order the index lists them (src/lessons/Lesson.h says how to add one).
#pragma once

#include "lessons/Lesson.h"

#include <string>
#include <vector>

namespace sl
{

const std::vector<Lesson>& lessonRegistry();
// Throws InputError naming --only and listing the lessons when `name` is not one.
const Lesson& findLesson(const std::string& name);

} // namespace sl
