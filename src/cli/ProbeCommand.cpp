// shadowlab probe: render one frame, replay one pixel on the technique's CPU twin with a recorder, and write what
// it did (src/probe/Probe.h): probe.json, probe.vtm (+ probe/ pieces), probe.png.
#include "cli/Commands.h"

#include "core/Error.h"
#include "core/Parse.h"
#include "frame/FrameResult.h"
#include "io/ImageIO.h"
#include "io/OutputDirectory.h"
#include "lightspace/CameraView.h"
#include "output/OutputWriter.h"
#include "pipeline/ShadowRenderer.h"
#include "probe/Probe.h"
#include "scene/Scene.h"
#include "techniques/Registry.h"

#include <vtkMultiBlockDataSet.h>

#include <iomanip>
#include <regex>

namespace sl
{
namespace
{

glm::ivec2 parsePixel(const std::string& text)
{
  static const std::regex pattern(R"((-?\d{1,7}),(-?\d{1,7}))");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
  {
    throw InputError("--pixel " + text + ": expected X,Y (integers, image coordinates, row 0 at the bottom)");
  }
  return { std::stoi(match[1]), std::stoi(match[2]) };
}

// --pick's value: "X,Y,Z", or "world X,Y,Z" as main joins the older two-word form.
struct PickedPoint
{
  glm::dvec3 point{ 0.0 };
  bool worldWord = false; // typed as `--pick world X,Y,Z`
};

PickedPoint parsePick(const std::string& pick)
{
  PickedPoint picked;
  std::string numbers = pick;
  const std::size_t space = pick.find(' ');
  if (space != std::string::npos)
  {
    if (pick.substr(0, space) != "world")
    {
      throw InputError("--pick " + pick + ": expected --pick X,Y,Z (a world point; `--pick world X,Y,Z` too)");
    }
    picked.worldWord = true;
    numbers = pick.substr(space + 1);
  }
  std::size_t start = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::size_t end = numbers.find(',', start);
    const bool last = axis == 2;
    if ((end == std::string::npos) != last)
    {
      throw InputError("--pick " + pick + ": expected three comma-separated numbers X,Y,Z (a world point)");
    }
    const std::optional<double> value = parseNumber(numbers.substr(start, last ? std::string::npos : end - start));
    if (!value || !std::isfinite(*value))
    {
      throw InputError("--pick " + pick + ": expected three comma-separated finite numbers X,Y,Z (a world point)");
    }
    picked.point[axis] = *value;
    start = end + 1;
  }
  return picked;
}

} // namespace

int runProbe(const ProbeOptions& options, std::ostream& log)
{
  // Everything the user typed is checked before the GPU or the disk is touched.
  if (options.pixel.empty() == options.pick.empty())
  {
    throw InputError("probe: give exactly one of --pixel X,Y and --pick X,Y,Z");
  }
  const std::optional<glm::ivec2> pixel =
    options.pixel.empty() ? std::nullopt : std::optional<glm::ivec2>(parsePixel(options.pixel));
  const std::optional<PickedPoint> pick =
    options.pick.empty() ? std::nullopt : std::optional<PickedPoint>(parsePick(options.pick));
  const TechniqueDescriptor& technique = findTechnique(options.technique);
  if (!technique.probe)
  {
    throw InputError("--technique " + technique.name + ": this technique has no probe recorder");
  }
  const CheckedFrameCommand checked = checkFrameCommand(options, "probe");
  const RenderRequest& request = checked.request;
  const Scene& scene = checked.scene;
  const OutputTarget& output = checked.output;
  reportDroppedTriangles(scene, options.sceneFile, log);
  ShadowRenderer renderer;
  const FrameResult frame = renderer.render(scene, request);
  glm::ivec2 probed{ 0 };
  if (pixel)
  {
    probed = *pixel;
  }
  else
  {
    // A visible point is within a fraction of a pixel's footprint of the G-buffer's surface point; the footprint
    // grows with the distance, so the tolerance is relative to it (1 %).
    const glm::dvec3 nearPoint = frame.camera.nearOrigin;
    try
    {
      probed = pickPixel(frame, pick->point, 0.01 * glm::length(pick->point - nearPoint) + 1e-6);
    }
    catch (const InputError& error)
    {
      // pickPixel names the point as `--pick world X,Y,Z`; say it as the user typed it.
      const std::string message = error.what();
      const std::string worldPrefix = "--pick world ";
      if (pick->worldWord || message.rfind(worldPrefix, 0) != 0)
      {
        throw;
      }
      throw InputError("--pick " + message.substr(worldPrefix.size()));
    }
  }
  const ProbeResult probe = probePixel(frame, scene, options.lightIndex, probed);
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    writeJson(probeJson(probe, frame, scene), dir / "probe.json");
    writeVtm(dir / "probe.vtm", probeDataSet(probe, frame, scene));
    writePng(dir / "probe.png", probeFigure(probe, frame, scene));
  });
  const std::string summary = format(frame.technique, " pixel ", probed.x, ",", probed.y, ": GPU visibility ",
    probe.gpuVisibility, ", twin ", probe.outcome.visibility, " (|difference| ", probe.difference(), ", tolerance ",
    probe.outcome.tolerance, ")");
  if (!probe.agrees())
  {
    log << "shadowlab: error: probe " << summary << ": the GPU and its CPU twin differ beyond the tests' tolerance ("
        << "files written to " << printable(options.outDir) << ")\n";
    return 3;
  }
  if (!probe.outcome.ambiguity.empty() && probe.difference() > probe.outcome.tolerance + 1e-6)
  {
    log << "shadowlab: warning: probe " << summary << ": differ at a decision within float rounding ("
        << probe.outcome.ambiguity << ")\n";
  }
  if (!options.quiet)
  {
    log << "shadowlab: probe " << summary << " -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
