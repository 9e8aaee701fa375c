#include "frame/Approximations.h"

#include "core/Error.h"

namespace sl
{

NamedImage approximationBuffer(const FrameResult& frame, const Scene& scene, int lightIndex)
{
  SL_CHECK_MSG(frame.descriptor, "frame of technique ", frame.technique, " has no descriptor");
  const AccuracyContract& contract = frame.descriptor->accuracy;
  ImageF codes(frame.resolution.x, frame.resolution.y, 1, 0.0f);
  if (contract.markApproximations && !contract.approximations.empty())
  {
    contract.markApproximations(ApproximationContext{ &frame, &scene, lightIndex }, codes);
  }
  const NamedImage* coverage = frame.find("coverage");
  const NamedImage* receives = frame.find("receives_shadows");
  const float highest = static_cast<float>(contract.approximations.size());
  for (int y = 0; y < codes.height; ++y)
  {
    for (int x = 0; x < codes.width; ++x)
    {
      float& code = codes.at(x, y);
      SL_CHECK_MSG(code >= 0.0f && code <= highest && code == static_cast<float>(static_cast<int>(code)),
        frame.technique, ": approximation code ", code, " at pixel ", x, ",", y, " is not declared");
      // A pixel without a surface, or one whose surface does not receive shadows, has nothing to approximate.
      if ((coverage && coverage->image.at(x, y) <= 0.5f) || (receives && receives->image.at(x, y) <= 0.5f))
      {
        code = 0.0f;
      }
    }
  }
  std::vector<std::string> labels = { kNoApproximation };
  for (const Approximation& approximation : contract.approximations)
  {
    labels.push_back(approximation.name);
  }
  std::string doc = "the technique's declared approximation that applies at the pixel (TechniqueDescriptor::accuracy): "
                    "0 none";
  for (std::size_t index = 0; index < contract.approximations.size(); ++index)
  {
    doc += ", " + std::to_string(index + 1) + " " + contract.approximations[index].name + " (" +
      contract.approximations[index].doc + ")";
  }
  return { kApproximationBuffer, std::move(codes), "", doc, BufferKind::Categorical, labels };
}

ApproximatePixels approximatePixels(const FrameResult& frame)
{
  ApproximatePixels result;
  const NamedImage* buffer = frame.find(kApproximationBuffer);
  if (!buffer)
  {
    return result;
  }
  std::vector<std::size_t> perCode(buffer->categoryLabels.size(), 0);
  for (const float code : buffer->image.data)
  {
    const auto index = static_cast<std::size_t>(code);
    if (code > 0.0f && index < perCode.size())
    {
      ++perCode[index];
      ++result.count;
    }
  }
  for (std::size_t code = 1; code < perCode.size(); ++code)
  {
    if (perCode[code] > 0)
    {
      result.byApproximation.emplace_back(buffer->categoryLabels[code], perCode[code]);
    }
  }
  return result;
}

} // namespace sl
