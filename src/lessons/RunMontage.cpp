#include "lessons/RunMontage.h"

#include "frame/FrameResult.h"
#include "techniques/Registry.h"
#include "vis/BufferHeatMap.h"

namespace sl
{

BufferSpec runBufferSpec(const nlohmann::json& stats, const std::string& buffer)
{
  std::vector<const std::vector<BufferSpec>*> lists = { &commonBufferSpecs(), &subLightBufferSpecs(), &multisampleBufferSpecs() };
  const nlohmann::json technique = stats.is_object() ? stats.value("technique", nlohmann::json()) : nlohmann::json();
  if (technique.is_string())
  {
    for (const TechniqueDescriptor& descriptor : techniqueRegistry())
    {
      if (descriptor.name == technique.get<std::string>())
      {
        lists.push_back(&descriptor.buffers);
      }
    }
  }
  for (const std::vector<BufferSpec>* list : lists)
  {
    for (const BufferSpec& spec : *list)
    {
      if (spec.name == buffer)
      {
        return spec;
      }
    }
  }
  BufferSpec spec;
  spec.name = buffer;
  const nlohmann::json summaries = stats.is_object() ? stats.value("buffers", nlohmann::json::object()) : nlohmann::json();
  if (summaries.is_object() && summaries.contains(buffer) && summaries[buffer].is_object() &&
    summaries[buffer].value("unit", nlohmann::json()).is_string())
  {
    spec.unit = summaries[buffer]["unit"].get<std::string>();
  }
  return spec;
}

ImageU8 runValueMask(const std::vector<NamedImage>& buffers, const NamedImage& values, const BufferSpec& spec)
{
  // Read back from buffers.vti, the image carries no domain: the declaration gives it.
  NamedImage declared{ values.name, ImageF(values.image.width, values.image.height, 1), values.unit, values.doc,
    spec.kind, {}, spec.domain };
  return bufferValueMask(declared, buffers);
}

ImageU8 coverageMask(const std::vector<NamedImage>& buffers)
{
  const NamedImage* coverage = findNamed(buffers, "coverage");
  return coverage ? coverageMask(*coverage) : ImageU8();
}

} // namespace sl
