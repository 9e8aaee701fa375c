#include "passes/GpuReceivers.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/PassUtilities.h"

#include <vtkTextureObject.h>

#include <cmath>
#include <cstring>

namespace sl
{
namespace
{

constexpr std::uint32_t untouchedMin = 0xFFFFFFFFu;

// A reduction's input appended to its memo key as bytes (bit-identical inputs, the same key).
template <class T>
void appendBytes(std::string& key, const T& value)
{
  key.append(reinterpret_cast<const char*>(&value), sizeof(value));
}
constexpr std::uint32_t untouchedMax = 0u;

std::unique_ptr<ComputeProgram> makeProgram(int pass)
{
  ShaderDefines defines = commonDefines();
  defines.push_back({ "FOCUS_PASS", std::to_string(pass) });
  return std::make_unique<ComputeProgram>(
    assembleShader("lightspace/FocusReduction.glsl", defines), "focus reduction " + std::to_string(pass));
}

} // namespace

float floatFromOrderedBits(std::uint32_t bits)
{
  const std::uint32_t raw = (bits & 0x80000000u) != 0u ? (bits & 0x7FFFFFFFu) : ~bits;
  float value = 0.0f;
  std::memcpy(&value, &raw, sizeof(value));
  return value;
}

GpuReceivers::GpuReceivers()
  : summaryProgram_(makeProgram(0))
  , extentProgram_(makeProgram(1))
  , result_(9)
{
}

GpuReceivers::~GpuReceivers() = default;

void GpuReceivers::setGBuffer(vtkTextureObject* gbufferPosition, vtkTextureObject* gbufferNormal)
{
  position_ = gbufferPosition;
  normal_ = gbufferNormal;
  reductions_.clear();
}

std::vector<std::uint32_t> GpuReceivers::run(const ComputeProgram& program, const Light& light, const std::string& query)
{
  SL_CHECK(position_ && normal_);
  std::string key = query;
  appendBytes(key, &program);
  appendBytes(key, lightTypeCode(light.type));
  appendBytes(key, light.center);
  appendBytes(key, light.normal);
  appendBytes(key, light.direction);
  appendBytes(key, light.coneAngleDeg);
  for (const glm::dvec4& plane : ownerPlanes())
  {
    appendBytes(key, plane);
  }
  if (const auto found = reductions_.find(key); found != reductions_.end())
  {
    return found->second;
  }
  program.use();
  position_->Activate();
  normal_->Activate();
  program.setInt("gbufferPosition", position_->GetTextureUnit());
  program.setInt("gbufferNormal", normal_->GetTextureUnit());
  program.setInt("lightType", lightTypeCode(light.type));
  program.setVector("lightCenterWs", light.center);
  program.setVector("lightNormalWs", light.normal);
  program.setVector("lightDirectionWs", light.direction);
  program.setFloat("lightCosCone", std::cos(glm::radians(light.coneAngleDeg)));
  SL_CHECK_MSG(ownerPlanes().size() <= 4, "at most 4 owner planes (FocusReduction.glsl MAX_OWNER_PLANES)");
  program.setInt("ownerPlaneCount", static_cast<int>(ownerPlanes().size()));
  program.setVectors("ownerPlanes", ownerPlanes());
  result_.bind(0);
  const glm::ivec2 size(static_cast<int>(position_->GetWidth()), static_cast<int>(position_->GetHeight()));
  // 8 x 8 invocations per group, each reducing an 8 x 8 pixel tile (FocusReduction.glsl).
  program.dispatch({ (size.x + 63) / 64, (size.y + 63) / 64 });
  position_->Deactivate();
  normal_->Deactivate();
  checkGlErrors("focus reduction");
  return reductions_[key] = result_.download();
}

ReceiverSummary GpuReceivers::summary(const Light& light)
{
  result_.upload({ untouchedMin, untouchedMin, untouchedMin, untouchedMax, untouchedMax, untouchedMax, 0u, 0u, 0u });
  const std::vector<std::uint32_t> words = run(*summaryProgram_, light, {});
  ReceiverSummary summary;
  summary.count = static_cast<int>(words[6]);
  if (summary.count > 0)
  {
    summary.worldBounds.extend({ floatFromOrderedBits(words[0]), floatFromOrderedBits(words[1]), floatFromOrderedBits(words[2]) });
    summary.worldBounds.extend({ floatFromOrderedBits(words[3]), floatFromOrderedBits(words[4]), floatFromOrderedBits(words[5]) });
  }
  return summary;
}

ReceiverExtent GpuReceivers::extent(const Light& light, const LightView& view, const glm::dvec3& axis)
{
  result_.upload(
    { untouchedMin, untouchedMax, untouchedMin, untouchedMax, untouchedMin, untouchedMax, untouchedMin, 0u, 0u });
  extentProgram_->setMatrix("lightViewFromWorld", view.viewFromWorld);
  extentProgram_->setInt("lightIsPerspective", view.projection == LightProjection::Perspective ? 1 : 0);
  extentProgram_->setVector("lightEyeWs", view.eyeWs);
  extentProgram_->setVector("lightAxisWs", axis);
  std::string query;
  appendBytes(query, view.viewFromWorld);
  appendBytes(query, view.projection);
  appendBytes(query, view.eyeWs);
  appendBytes(query, axis);
  const std::vector<std::uint32_t> words = run(*extentProgram_, light, query);
  ReceiverExtent extent;
  extent.inFront = static_cast<int>(words[7]);
  extent.reachable = static_cast<int>(words[8]);
  if (extent.inFront > 0)
  {
    extent.minXY = { floatFromOrderedBits(words[0]), floatFromOrderedBits(words[2]) };
    extent.maxXY = { floatFromOrderedBits(words[1]), floatFromOrderedBits(words[3]) };
    extent.minDepth = floatFromOrderedBits(words[4]);
    extent.maxDepth = floatFromOrderedBits(words[5]);
  }
  if (words[6] != untouchedMin)
  {
    extent.minCosToAxis = floatFromOrderedBits(words[6]);
  }
  return extent;
}

} // namespace sl
