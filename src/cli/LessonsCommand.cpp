// shadowlab lessons [--out DIR] [--resolution WxH] [--only NAME]... [--list]: the lesson pages (src/lessons/), each
// generated from runs made now, into shadowlab-lessons by default (`--out docs/lessons` regenerates the source tree's
// pages). --out is written atomically as a whole (io/OutputDirectory.h); with --only, the
// other lessons of an existing --out that shadowlab wrote are carried over unchanged, so one lesson can be
// regenerated alone.
#include "cli/Commands.h"

#include "cli/CommandProgress.h"
#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "lessons/LessonBuilder.h"
#include "lessons/LessonRegistry.h"

#include <algorithm>
#include <chrono>
#include <iomanip>

namespace sl
{

namespace fs = std::filesystem;

int runLessons(const LessonsOptions& options, std::ostream& log)
{
  if (options.list)
  {
    // The names --only takes, with the pages' headings: nothing is run or written.
    for (const Lesson& lesson : lessonRegistry())
    {
      log << lesson.name << " - " << lesson.title << "\n";
    }
    return 0;
  }
  LessonsSettings settings;
  settings.resolution = parseResolution(options.resolution);
  settings.datasets = fs::path(SL_SOURCE_DIR) / "datasets";
  std::vector<const Lesson*> selected;
  for (const std::string& name : options.only)
  {
    const Lesson* lesson = &findLesson(name);
    if (std::find(selected.begin(), selected.end(), lesson) == selected.end())
    {
      selected.push_back(lesson);
    }
  }
  if (options.only.empty())
  {
    for (const Lesson& lesson : lessonRegistry())
    {
      selected.push_back(&lesson);
    }
  }
  settings.command = "shadowlab lessons --out " + options.outDir + " --resolution " + options.resolution;
  for (const Lesson* lesson : selected)
  {
    settings.command += options.only.empty() ? "" : " --only " + lesson->name;
  }

  const OutputTarget output{ options.outDir, "lessons", options.force, { settings.datasets } };
  checkOutputTarget(output);
  const fs::path previous = options.outDir;
  std::error_code error;
  const bool keepOthers = !options.only.empty() && fs::is_regular_file(previous / kOutputMarkerName, error);
  const auto start = std::chrono::steady_clock::now();
  writeDirectoryAtomically(output, [&](const fs::path& dir) {
    if (keepOthers)
    {
      for (const Lesson& lesson : lessonRegistry())
      {
        const bool regenerated = std::find(selected.begin(), selected.end(), &lesson) != selected.end();
        std::error_code copyError;
        if (!regenerated && fs::is_directory(previous / lesson.name, copyError))
        {
          fs::copy(previous / lesson.name, dir / lesson.name, fs::copy_options::recursive, copyError);
          if (copyError)
          {
            throw InputError("--out " + printable(options.outDir) + ": cannot keep lesson " + lesson.name + " (" +
              copyError.message() + ")");
          }
        }
      }
    }
    const ProgressSwitches switches{ options.progress, options.quiet };
    Progress progress("lessons", format(selected.size(), " lesson(s) at ", options.resolution), "lesson",
      selected.size(), commandProgressStream(switches, log), commandProgressSettings(switches));
    writeLessons(selected, settings, dir, [&progress](std::size_t done) { progress.step(done); });
    progress.finish();
  });
  if (!options.quiet)
  {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log << "shadowlab: " << selected.size() << " lesson(s) at " << options.resolution << " in " << std::fixed
        << std::setprecision(1) << seconds << " s -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
