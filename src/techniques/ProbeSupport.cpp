#include "techniques/ProbeSupport.h"

#include "core/Error.h"

#include <utility>

namespace sl
{

ShadowMapInputs shadowMapInputsOf(
  const FrameResult& frame, const Scene& scene, int lightIndex, bool withWindowDepth, int view)
{
  SL_CHECK_MSG(frame.lightView.has_value(), "technique ", frame.technique, " rendered no shadow map");
  SL_CHECK_MSG(frame.partitions.has_value() == (view >= 0), "technique ", frame.technique,
    ": a partitioned frame's inputs name their view, and only such a frame's");
  const std::string suffix = view >= 0 ? partitionViewSuffix(*frame.partitions, view) : "";
  ShadowMapInputs inputs;
  inputs.light = &scene.lights.at(static_cast<std::size_t>(lightIndex));
  inputs.camera = frame.camera;
  inputs.lightView = view >= 0 ? frame.partitions->views.at(static_cast<std::size_t>(view)) : *frame.lightView;
  inputs.position = frame.find("position")->image;
  inputs.normal = frame.find("normal")->image;
  inputs.coverage = frame.find("coverage")->image;
  inputs.receives = frame.find("receives_shadows")->image;
  for (const NamedImage& named : frame.lightSpace)
  {
    if (named.name == "shadow_map_depth" + suffix)
    {
      inputs.shadowMapLinear = named.image;
    }
    else if (withWindowDepth && named.name == "shadow_map_window_depth" + suffix)
    {
      inputs.shadowMapWindow = named.image;
    }
    else if (named.name == "shadow_map_polygon_id")
    {
      inputs.shadowMapPolygonId = named.image;
    }
  }
  if (const NamedImage* ids = frame.find("polygon_id"))
  {
    inputs.receiverPolygonId = ids->image;
  }
  return inputs;
}

std::vector<ShadowMapInputs> viewInputsOf(
  const FrameResult& frame, const Scene& scene, int lightIndex, bool withWindowDepth)
{
  std::vector<ShadowMapInputs> inputs;
  if (!frame.partitions)
  {
    inputs.push_back(shadowMapInputsOf(frame, scene, lightIndex, withWindowDepth));
    return inputs;
  }
  for (int k = 0; k < frame.partitions->viewCount(); ++k)
  {
    inputs.push_back(shadowMapInputsOf(frame, scene, lightIndex, withWindowDepth, k));
  }
  return inputs;
}

ReferenceSample partitionedReference(const FrameResult& frame, const std::vector<ShadowMapInputs>& inputs, int x,
  int y, const ShadowMapTwin& twin, ProbeRecorder* recorder)
{
  if (!frame.partitions)
  {
    return twin(inputs.front(), x, y, recorder);
  }
  const ShadowMapInputs& any = inputs.front();
  const glm::dvec3 pWs(any.position.at(x, y, 0), any.position.at(x, y, 1), any.position.at(x, y, 2));
  const PartitionSet& partitions = *frame.partitions;
  const ViewSelection selection = selectView(partitions, frame.camera, pWs);
  if (recorder && partitions.kind == PartitionKind::Cascades)
  {
    recorder->beginGroup("cascade");
    recorder->quantity("cascade", selection.primary, "", "survey §4.3.1: the map the pixel reads (selectCascade)");
    if (selection.primaryWeight < 1.0)
    {
      recorder->quantity("blended cascade", selection.secondary, "", "cascade_blend: the next cascade");
      recorder->quantity("primary weight", selection.primaryWeight, "", "");
    }
  }
  if (recorder && partitions.kind == PartitionKind::CubeFaces)
  {
    recorder->beginGroup("cube face");
    recorder->quantity("cube face", cubeFaceOf(partitions, pWs), "",
      "survey §2: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z, the dominant axis of p - light centre (selectCubeFace)");
  }
  ReferenceSample sample = twin(inputs.at(static_cast<std::size_t>(selection.primary)), x, y, recorder);
  if (selection.primaryWeight < 1.0 && sample.evaluated)
  {
    const ReferenceSample other = twin(inputs.at(static_cast<std::size_t>(selection.secondary)), x, y, nullptr);
    sample.visibility = selection.primaryWeight * sample.visibility + (1.0 - selection.primaryWeight) * other.visibility;
    sample.depthMargin = std::min(sample.depthMargin, other.depthMargin);
    sample.texelEdgeMargin = std::min(sample.texelEdgeMargin, other.texelEdgeMargin);
  }
  return sample;
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
