// Triangle-mesh files (OBJ, PLY, OFF, STL, whatever OpenMesh's readers take) -> TriangleMesh.
//
// What the loader refuses (InputError naming the file, and the line or element):
//  - OBJ: a `v`/`vt`/`vn` line whose numbers are not finite 32-bit floats (`nan`, `inf`, `1e999`) or are too
//    few, a face with fewer than 3 corners, and any vertex / texture / normal index that is 0, out of range,
//    or relative (negative) reaching before the first element: "<file>:<line>: <problem>". OpenMesh would
//    skip such a line and silently shift every later index. ASCII PLY, OFF and STL vertex records likewise
//    ("<file>:<line>: vertex <i>: ...").
//  - Every format: a vertex whose coordinates, file normal or texture coordinate are not finite ("vertex <i>",
//    in file order),
//    a face naming a vertex that does not exist ("face <i>"), and fewer vertices or faces than the file
//    declares (PLY/OFF header, binary STL facet count, OBJ lines): nothing OpenMesh skips goes unnoticed.
//  - A file with no faces, or with only degenerate triangles.
//
// What the loader guarantees about the result:
//  - Only non-degenerate triangles are kept. Degenerate are: the triangles of a face that names a vertex
//    more than once (PLY/OFF/STL: the whole face, n - 2 triangles; OBJ: OpenMesh keeps the face's distinct
//    corners in order, so `f 1 2 2 3` is the triangle 1 2 3 and `f 1 1 2` nothing, and the
//    n - max(distinct, 2) triangles lost count), and triangles of zero area (twice the area below 1e-10
//    times the longest edge squared, i.e. collinear up to float rounding). Dropped triangles are counted;
//    vertices used by no kept triangle are removed.
//  - Polygons are fan-triangulated (OpenMesh's TriMesh does this on insertion); the file's winding is kept.
//  - Normals: the file's vertex normals when it has them (renormalised); otherwise, and for any vertex
//    whose file normal is zero or missing (STL has only facet normals), area-weighted smooth normals of the
//    kept triangles.
//  - Texture coordinates: per vertex (OBJ `vt`, PLY u/v) when the file has them, else `uvs` is empty; a
//    vertex the file gives none (an OBJ vertex only used by faces without `vt`) gets (0, 0).
//    OpenMesh stores one texture coordinate per vertex, so an OBJ that gives a vertex different `vt` on
//    different faces (a UV seam) keeps the last one it read.
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
// unreadable or corrupt, breaks one of the rules above, has no faces, or has only degenerate triangles.
LoadedMesh loadMesh(const std::filesystem::path& file);

} // namespace sl
