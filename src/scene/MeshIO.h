// Triangle-mesh files (OBJ, PLY, OFF, STL, whatever OpenMesh's readers take) -> TriangleMesh.
//
// What the loader guarantees about the result:
//  - Only non-degenerate triangles are kept. A triangle is degenerate when a corner is NaN/inf or its area
//    is zero (twice its area below 1e-10 times its longest edge squared, i.e. collinear up to float
//    rounding). Dropped triangles are counted; vertices used by no kept triangle are removed.
//  - Polygons are fan-triangulated (OpenMesh's TriMesh does this on insertion); the file's winding is kept.
//  - Normals: the file's vertex normals when it has them (renormalised); otherwise, and for any vertex
//    whose file normal is zero or not finite, area-weighted smooth normals of the kept triangles.
//  - Texture coordinates: per vertex (OBJ `vt`, PLY u/v) when the file has them, else `uvs` is empty.
//    OpenMesh stores one texture coordinate per vertex, so an OBJ that gives a vertex different `vt` on
//    different faces (a UV seam) keeps the last one it read.
//  - Faces OpenMesh itself refuses (a face naming the same vertex twice) never reach us and are not
//    counted.
// OpenMesh's console output is silenced while reading; problems come back as InputError instead.
#pragma once

#include "scene/Scene.h"

#include <cstddef>
#include <filesystem>

namespace sl
{

struct LoadedMesh
{
  TriangleMesh mesh; // in the file's coordinates
  std::size_t droppedDegenerateTriangles = 0;
};

// Reads `file`. Throws InputError (message names the file, no scene context) when the file is missing,
// unreadable or corrupt, has no faces, or has only degenerate triangles.
LoadedMesh loadMesh(const std::filesystem::path& file);

} // namespace sl
