#include "objectspace/SilhouetteExport.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

namespace sl
{

vtkSmartPointer<vtkPolyData> silhouettePolyData(const std::vector<SilhouetteEdge>& silhouettes)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(2 * silhouettes.size()));
  vtkNew<vtkCellArray> lines;
  const auto makeArray = [&silhouettes](const char* name) {
    vtkNew<vtkIntArray> array;
    array->SetName(name);
    array->SetNumberOfTuples(static_cast<vtkIdType>(silhouettes.size()));
    return vtkSmartPointer<vtkIntArray>(array);
  };
  const vtkSmartPointer<vtkIntArray> casterIds = makeArray("caster_id");
  const vtkSmartPointer<vtkIntArray> multiplicities = makeArray("multiplicity");
  const vtkSmartPointer<vtkIntArray> incidentTriangles = makeArray("incident_triangles");
  for (std::size_t index = 0; index < silhouettes.size(); ++index)
  {
    const SilhouetteEdge& edge = silhouettes[index];
    const auto id = static_cast<vtkIdType>(index);
    points->SetPoint(2 * id, edge.from.x, edge.from.y, edge.from.z);
    points->SetPoint(2 * id + 1, edge.to.x, edge.to.y, edge.to.z);
    const vtkIdType line[2] = { 2 * id, 2 * id + 1 };
    lines->InsertNextCell(2, line);
    casterIds->SetValue(id, static_cast<int>(edge.objectIndex));
    multiplicities->SetValue(id, edge.multiplicity);
    incidentTriangles->SetValue(id, static_cast<int>(edge.incidentTriangles));
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetLines(lines);
  polyData->GetCellData()->AddArray(casterIds);
  polyData->GetCellData()->AddArray(multiplicities);
  polyData->GetCellData()->AddArray(incidentTriangles);
  return polyData;
}

} // namespace sl
