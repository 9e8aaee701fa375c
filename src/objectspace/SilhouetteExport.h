// The object-space export of technique `shadow-volume`: its silhouette edges as a vtkPolyData of lines
// (written as silhouettes.vtp beside light_space.vti), openable in ParaView.
//  cell data  caster_id           int  the caster's index in the scene's objects
//             multiplicity        int  |m|, the number of side quads drawn for the edge (ShadowVolumeGeometry.h)
//             incident_triangles  int  1 boundary, 2 manifold, > 2 non-manifold
// Each line runs in the direction the light-oriented triangles run along the edge, so the side quads lie
// to its right seen from the light (ShadowVolumeGeometry.h, rule 2).
#pragma once

#include "objectspace/ShadowVolumeGeometry.h"

#include <vtkSmartPointer.h>

#include <vector>

class vtkPolyData;

namespace sl
{

vtkSmartPointer<vtkPolyData> silhouettePolyData(const std::vector<SilhouetteEdge>& silhouettes);

} // namespace sl
