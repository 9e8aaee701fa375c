// shadowlab view: a desktop window on the offscreen pipeline's frames. The order is the CLI's contract: every
// input the user typed is checked first (exit 1, one line), then the display (exit 2, one line, before any
// window or frame), then the pipeline renders the first frame, and only then does a window open.
#include "cli/Commands.h"

#include "cli/ViewerSession.h"
#include "cli/ViewerWindow.h"
#include "cli/XDisplay.h"
#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "techniques/Registry.h"

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
  }
  std::error_code error;
  if (fs::exists(options.screenshotDir, error) && !fs::is_directory(options.screenshotDir, error))
  {
    throw InputError("--screenshot-dir " + printable(options.screenshotDir) + ": exists and is not a directory");
  }
}

// The first line VTK's event recorder (vtkInteractorEventRecorder) writes: what makes a file a recording.
constexpr const char* kRecordingHeader = "# StreamVersion ";

bool isRecording(const fs::path& file)
{
  std::ifstream stream(file, std::ios::binary);
  std::string firstLine;
  return std::getline(stream, firstLine) && firstLine.rfind(kRecordingHeader, 0) == 0;
}

// --record empties its file when the window opens: never an input of the session (read, or read again when a
// key reloads the scene), and an existing file only when it is an earlier recording or the user said --force.
// Checked once the session has loaded the scene (its meshes and textures are known) and before the display.
void checkRecordTarget(const ViewOptions& options, const std::vector<fs::path>& inputs)
{
  if (options.recordFile.empty())
  {
    return;
  }
  const std::string named = "--record " + printable(options.recordFile);
  if (const std::string reason = inputConflict(options.recordFile, inputs); !reason.empty())
  {
    throw InputError(named + ": refused, it " + printable(reason) + " (nothing was written)");
  }
  std::error_code error;
  const fs::file_status status = fs::status(options.recordFile, error);
  if (!fs::exists(status))
  {
    return;
  }
  if (!fs::is_regular_file(status))
  {
    throw InputError(named + ": exists and is not a regular file; not replaced");
  }
  if (!options.force && !isRecording(options.recordFile))
  {
    throw InputError(named + ": refused, the file exists and is not a recording (its first line is not \"" +
      std::string(kRecordingHeader) + "...\"); choose another --record, or add --force to replace it");
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
  checkSceneOverrides(options.sceneOverrides);
  checkEventFiles(options);
  // Declared in this order so that they go in the reverse: the window (its GLX context) before the pipeline
  // (its EGL context, ViewerSession.h), and the X connection after the window.
  ViewerSession session(start); // the technique, its settings, the scene
  std::vector<fs::path> inputs = sceneInputs(session.scene(), options.sceneFile);
  const std::vector<fs::path> parameterFiles = fileParameterInputs(findTechnique(options.technique), options.settings);
  inputs.insert(inputs.end(), parameterFiles.begin(), parameterFiles.end());
  if (!options.playFile.empty())
  {
    inputs.emplace_back(options.playFile); // it would be emptied before it is read
  }
  checkRecordTarget(options, inputs);
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
