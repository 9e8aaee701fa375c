#include "frame/ProbeRecord.h"

#include <utility>

namespace sl
{

const ProbeQuantity* ProbeRecord::find(const std::string& name) const
{
  for (const ProbeQuantity& quantity : quantities)
  {
    if (quantity.name == name)
    {
      return &quantity;
    }
  }
  return nullptr;
}

void ProbeRecorder::add(const std::string& name, std::vector<double> value, const std::string& unit,
  const std::string& source)
{
  record_.quantities.push_back({ group_, name, std::move(value), unit, source, {} });
}

void ProbeRecorder::quantity(const std::string& name, double value, const std::string& unit, const std::string& source)
{
  add(name, { value }, unit, source);
}

void ProbeRecorder::quantity(
  const std::string& name, const glm::dvec2& value, const std::string& unit, const std::string& source)
{
  add(name, { value.x, value.y }, unit, source);
}

void ProbeRecorder::quantity(
  const std::string& name, const glm::dvec3& value, const std::string& unit, const std::string& source)
{
  add(name, { value.x, value.y, value.z }, unit, source);
}

void ProbeRecorder::category(const std::string& name, const std::string& label, const std::string& source)
{
  record_.quantities.push_back({ group_, name, {}, "", source, label });
}

void ProbeRecorder::category(const std::string& name, int code, const std::string& label, const std::string& source)
{
  record_.quantities.push_back({ group_, name, { static_cast<double>(code) }, "code", source, label });
}

void ProbeRecorder::texel(ProbeTexel texel)
{
  if (record_.texels.size() >= kMaxTexels)
  {
    ++record_.droppedTexels;
    return;
  }
  record_.texels.push_back(std::move(texel));
}

void ProbeRecorder::node(ProbeNode node)
{
  if (record_.nodes.size() >= kMaxNodes)
  {
    ++record_.droppedNodes;
    return;
  }
  record_.nodes.push_back(std::move(node));
}

void ProbeRecorder::kernel(ProbeKernel kernel)
{
  record_.kernels.push_back(std::move(kernel));
}

void ProbeRecorder::mapPolygon(ProbeMapPolygon polygon)
{
  record_.mapPolygons.push_back(std::move(polygon));
}

void ProbeRecorder::lightPolygon(ProbeLightPolygon polygon)
{
  if (record_.lightPolygons.size() >= kMaxPolygons)
  {
    ++record_.droppedPolygons;
    return;
  }
  record_.lightPolygons.push_back(std::move(polygon));
}

void ProbeRecorder::contourEdge(const ProbeContourEdge& edge)
{
  if (record_.contourEdges.size() >= kMaxEdges)
  {
    ++record_.droppedEdges;
    return;
  }
  record_.contourEdges.push_back(edge);
}

void ProbeRecorder::lightSample(const ProbeLightSample& sample)
{
  record_.lightSamples.push_back(sample);
}

} // namespace sl
