// A lesson (`shadowlab lessons`, issue 15): one question about a shadow algorithm, answered by real runs. A lesson is
// data plus one function that asks a LessonBuilder for runs, figures, measured numbers and commands to try next;
// the builder renders, measures and writes the page, so no number on a page is typed by hand.
//
// Adding a lesson: one file in src/lessons/ defining `Lesson <name>Lesson()`, its declaration and one line in
// LessonRegistry.cpp, and the file in src/lessons/sources.cmake. The tests regenerate every registered lesson.
#pragma once

#include <functional>
#include <string>

namespace sl
{

class LessonBuilder;

struct Lesson
{
  std::string name;     // folder and --only name, e.g. "acne-and-bias"
  std::string title;    // the page's heading
  std::string question; // what the page answers, one or two sentences of Markdown
  std::function<void(LessonBuilder&)> build;
};

} // namespace sl
