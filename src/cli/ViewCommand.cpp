// shadowlab view: a desktop window on the offscreen pipeline's frames. The order is the CLI's contract: every
// input the user typed is checked first (exit 1, one line), then the display (exit 2, one line, before any
// window or frame), then the pipeline renders the first frame, and only then does a window open.
#include "cli/Commands.h"

#include "cli/ViewerSession.h"
#include "cli/ViewerWindow.h"
#include "cli/XDisplay.h"
#include "core/Error.h"

#include <filesystem>
#include <fstream>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

void checkEventFiles(const ViewOptions& options)
{
  if (!options.playFile.empty())
  {
    std::error_code error;
    if (!fs::is_regular_file(options.playFile, error) || !std::ifstream(options.playFile).good())
    {
      throw InputError("--play " + printable(options.playFile) + ": not a readable file");
    }
  }
  if (!options.recordFile.empty())
  {
    const fs::path record = fs::absolute(options.recordFile).lexically_normal();
    std::error_code error;
    if (fs::is_directory(record, error))
    {
      throw InputError("--record " + printable(options.recordFile) + ": is a directory");
    }
    if (!fs::is_directory(record.parent_path(), error))
    {
      throw InputError("--record " + printable(options.recordFile) + ": its directory does not exist");
    }
    if (!options.playFile.empty() && fs::equivalent(options.playFile, options.recordFile, error))
    {
      throw InputError("--record " + printable(options.recordFile) + ": is the --play file (it would be emptied)");
    }
  }
  std::error_code error;
  if (fs::exists(options.screenshotDir, error) && !fs::is_directory(options.screenshotDir, error))
  {
    throw InputError("--screenshot-dir " + printable(options.screenshotDir) + ": exists and is not a directory");
  }
}

} // namespace

int runView(const ViewOptions& options, std::ostream& out)
{
  ViewerStart start;
  start.sceneFile = options.sceneFile;
  start.sceneOverrides = options.sceneOverrides;
  start.technique = options.technique;
  start.settings = options.settings;
  start.lightIndex = options.lightIndex;
  if (!options.resolution.empty())
  {
    start.resolution = parseResolution(options.resolution);
  }
  checkEventFiles(options);
  // Declared in this order so that they go in the reverse: the window (its GLX context) before the pipeline
  // (its EGL context, ViewerSession.h), and the X connection after the window.
  ViewerSession session(start); // the technique, its settings, the scene
  const XDisplay display;
  session.renderFirstFrame();
  ViewerWindow window(session, display.handle(), options.sceneFile, options.screenshotDir, out);
  window.show();
  if (!options.recordFile.empty())
  {
    window.record(options.recordFile);
  }
  if (!options.playFile.empty())
  {
    window.play(options.playFile);
  }
  else
  {
    window.run();
  }
  return 0;
}

} // namespace sl
