#include "techniques/ProbeSupport.h"

#include "core/Error.h"

#include <utility>

namespace sl
{

ShadowMapInputs shadowMapInputsOf(const FrameResult& frame, const Scene& scene, int lightIndex, bool withWindowDepth)
{
  SL_CHECK_MSG(frame.lightView.has_value(), "technique ", frame.technique, " rendered no shadow map");
  ShadowMapInputs inputs;
  inputs.light = &scene.lights.at(static_cast<std::size_t>(lightIndex));
  inputs.camera = frame.camera;
  inputs.lightView = *frame.lightView;
  inputs.position = frame.find("position")->image;
  inputs.normal = frame.find("normal")->image;
  inputs.coverage = frame.find("coverage")->image;
  inputs.receives = frame.find("receives_shadows")->image;
  for (const NamedImage& named : frame.lightSpace)
  {
    if (named.name == "shadow_map_depth")
    {
      inputs.shadowMapLinear = named.image;
    }
    else if (withWindowDepth && named.name == "shadow_map_window_depth")
    {
      inputs.shadowMapWindow = named.image;
    }
  }
  return inputs;
}

void noteAmbiguity(std::string& ambiguity, const char* what, double margin, double threshold)
{
  if (margin < threshold)
  {
    ambiguity += (ambiguity.empty() ? "" : ", ") + std::string(what) + " " + format(margin);
  }
}

std::string ambiguityOf(const ReferenceSample& sample)
{
  std::string ambiguity;
  noteAmbiguity(ambiguity, "depth comparison within (relative)", sample.depthMargin, probeDepthAmbiguity);
  noteAmbiguity(ambiguity, "tap from a texel edge (texels)", sample.texelEdgeMargin, probeTexelEdgeAmbiguity);
  noteAmbiguity(ambiguity, "light-reach cosine", sample.reachMargin, probeReachAmbiguity);
  return ambiguity;
}

ProbeOutcome probeOutcome(const ReferenceSample& sample, double tolerance, std::string twin)
{
  ProbeOutcome outcome;
  outcome.evaluated = sample.evaluated;
  outcome.visibility = sample.visibility;
  outcome.tolerance = tolerance;
  outcome.ambiguity = sample.evaluated ? ambiguityOf(sample) : std::string();
  outcome.twin = std::move(twin);
  return outcome;
}

double bufferValue(const FrameResult& frame, const std::string& buffer, glm::ivec2 pixel)
{
  const NamedImage* named = frame.find(buffer);
  SL_CHECK_MSG(named != nullptr, "frame of ", frame.technique, " has no buffer ", buffer);
  return named->image.at(pixel.x, pixel.y);
}

glm::dvec3 bufferVector(const FrameResult& frame, const std::string& buffer, glm::ivec2 pixel)
{
  const NamedImage* named = frame.find(buffer);
  SL_CHECK_MSG(named != nullptr && named->image.components >= 3, "frame of ", frame.technique, " has no 3-component buffer ", buffer);
  return glm::dvec3(named->image.at(pixel.x, pixel.y, 0), named->image.at(pixel.x, pixel.y, 1), named->image.at(pixel.x, pixel.y, 2));
}

bool litWithoutShadowTest(const FrameResult& frame, glm::ivec2 pixel, ProbeRecorder& recorder, ProbeOutcome& outcome)
{
  if (bufferValue(frame, "receives_shadows", pixel) <= 0.5)
  {
    outcome.visibility = 1.0;
    recorder.category("receives_shadows", "no: lit, no shadow test", "ShadowLab (receive_shadows)");
    return true;
  }
  return false;
}

void requireSingleSubLight(const FrameResult& frame)
{
  const int perSide = frame.descriptor != nullptr ? frame.descriptor->subLightsPerSide(frame.parameters) : 1;
  if (perSide > 1)
  {
    throw InputError("--set sublights=" + std::to_string(perSide) +
      ": probe replays one shadow map; a frame keeps only the first sub-light's (use sublights=1)");
  }
}

} // namespace sl
