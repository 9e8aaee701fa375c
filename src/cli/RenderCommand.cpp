// shadowlab render: one scene, one technique, one frame; the image, the visibility and the technique's
// internal buffers are written to --out (src/output/OutputWriter.h).
#include "cli/Commands.h"

#include "core/Error.h"
#include "core/Progress.h"
#include "output/OutputWriter.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/Scene.h"
#include "techniques/Registry.h"

#include <iomanip>

namespace sl
{

int runRender(const RenderOptions& options, std::ostream& log)
{
  // Validate everything the user typed before touching the GPU or the disk.
  const CheckedFrameCommand checked = checkFrameCommand(options, "render");
  const RenderRequest& request = checked.request;
  const Scene& scene = checked.scene;
  const OutputTarget& output = checked.output;
  const std::size_t dropped = reportDroppedTriangles(scene, options.sceneFile, log);
  ShadowRenderer renderer;
  // Passes with long CPU-side loops (reference-sm's maps, dcs's wedges) print an estimate and progress when the
  // frame is expected to take long (core/Progress.h, 20 s); --quiet keeps them silent unless --progress.
  const ProgressStreamScope progress(options.quiet && !options.progress ? nullptr : &log);
  const FrameResult frame = renderer.render(scene, request);
  OutputContext context;
  context.sceneFile = options.sceneFile;
  context.lightIndex = options.lightIndex;
  context.droppedDegenerateTriangles = dropped;
  writeFrameOutputs(frame, context, output);
  reportCutShortPixels(frame, log);
  reportFlaggedPixels(frame, log);
  reportApproximatePixels(frame, log);
  if (!options.quiet)
  {
    double gpuMs = 0.0;
    for (const StageTiming& stage : frame.stages)
    {
      gpuMs += stage.gpuMs;
    }
    // The map's size as rendered; "(auto)" when shadow_map_size = auto chose it.
    std::string map;
    if (const std::optional<int> size = frame.shadowMapSize())
    {
      map = format(", shadow map ", *size, "^2", frame.automaticMapSize ? " (auto)" : "");
    }
    log << "shadowlab: rendered " << printable(options.sceneFile) << " with " << frame.technique << " at " << frame.resolution.x
        << "x" << frame.resolution.y << map << " on " << frame.glRenderer << ": GPU " << std::fixed << std::setprecision(2)
        << gpuMs << " ms, frame " << frame.frameWallMs << " ms -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
