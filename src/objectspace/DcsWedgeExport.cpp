#include "objectspace/DcsWedgeExport.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>

namespace sl
{

vtkSmartPointer<vtkPolyData> wedgePolyData(const DcsEdgeSet& wedges, const Light& light, const Bounds& sceneBounds)
{
  const std::vector<glm::dvec3> outline = lightOutline(light);
  const double reach = 2.0 * sceneBounds.radius() + glm::length(light.center - sceneBounds.center());
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> quads;
  const auto intArray = [](const char* name) {
    vtkNew<vtkIntArray> array;
    array->SetName(name);
    return vtkSmartPointer<vtkIntArray>(array.Get());
  };
  const auto wedgeIds = intArray("wedge_id");
  const auto casterIds = intArray("caster_id");
  const auto triangles = intArray("triangles");
  const auto incident = intArray("incident_triangles");
  const auto centre = intArray("centre_silhouette");
  for (std::size_t index = 0; index < wedges.wedges.size(); ++index)
  {
    const DcsWedgeEdge& wedge = wedges.wedges[index];
    const std::array<int, 2> supporting = wedgeSupportingCorners(wedge, outline);
    for (const int corner : supporting)
    {
      if (corner < 0)
      {
        continue;
      }
      const glm::dvec3& from = outline[static_cast<std::size_t>(corner)];
      const auto extruded = [&](const glm::dvec3& q) { return q + reach * glm::normalize(q - from); };
      const glm::dvec3 quad[4] = { wedge.v0, wedge.v1, extruded(wedge.v1), extruded(wedge.v0) };
      vtkIdType ids[4];
      for (int k = 0; k < 4; ++k)
      {
        ids[k] = points->InsertNextPoint(quad[k].x, quad[k].y, quad[k].z);
      }
      quads->InsertNextCell(4, ids);
      wedgeIds->InsertNextValue(static_cast<int>(index));
      casterIds->InsertNextValue(static_cast<int>(wedge.objectIndex));
      triangles->InsertNextValue(wedge.oppositeCount);
      incident->InsertNextValue(static_cast<int>(wedge.incidentTriangles));
      centre->InsertNextValue(wedge.silhouetteFromCentre ? 1 : 0);
    }
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(quads);
  for (vtkIntArray* array : { wedgeIds.Get(), casterIds.Get(), triangles.Get(), incident.Get(), centre.Get() })
  {
    polyData->GetCellData()->AddArray(array);
  }
  return polyData;
}

} // namespace sl
