// The object-space export of technique `dcs`: its wedges as a vtkPolyData (written as wedges.vtp beside
// silhouettes.vtp), openable in ParaView. Each wedge is drawn as its two supporting faces, the quads through its edge
// and the light's outline corners whose planes touch the light (the penumbra wedge's front and back planes,
// DcsGeometry.h wedgeSupportingCorners), extruded away from those corners to the far side of the scene's bounds.
//  cell data  wedge_id            int  index of the wedge (record) in the frame's list
//             caster_id           int  the caster's index in the scene's objects
//             triangles           int  the edge's triangles this record holds (1 or 2)
//             incident_triangles  int  of the whole welded edge: 1 boundary, 2 manifold, > 2 non-manifold
//             centre_silhouette   int  1 when the edge is a silhouette from the light's centre
#pragma once

#include "scene/Scene.h"
#include "objectspace/DcsGeometry.h"

#include <vtkSmartPointer.h>

class vtkPolyData;

namespace sl
{

vtkSmartPointer<vtkPolyData> wedgePolyData(const DcsEdgeSet& wedges, const Light& light, const Bounds& sceneBounds);

} // namespace sl
