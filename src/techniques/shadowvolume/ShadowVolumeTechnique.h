// Technique `shadow-volume`: exact hard shadows by z-fail stencil shadow volumes (Crow 1977; z-fail: Carmack
// 2000, Everitt & Kilgard 2002), the first technique that draws the scene's geometry itself (issue 12's
// object-space seam). For the light's centre (point, spot, directional, and the centre of an area light).
//
// Per frame:
//  1. CPU: the welded casters' volumes for this light (ShadowVolumeGeometry.h: every triangle oriented
//     toward the light, per-edge multiplicity, |m| side quads, near and far caps), uploaded as one vertex
//     buffer. CPU-built geometry rather than a geometry shader: the issue measured the latter 2-8x slower on
//     llvmpipe.
//  2. GPU, into the G-buffer's depth-stencil: every volume triangle rasterised (GL_DEPTH_CLAMP: volumes reach
//     infinity and are not clipped at the far plane; no culling), a fragment kept only where the triangle
//     meets the pixel's camera ray at or behind the visible point (z-fail; found from the triangle's plane,
//     vtkSLShadowVolumePass.h says why not from the depth test); two-sided stencil back faces
//     GL_INCR_WRAP, front faces GL_DECR_WRAP, and the same +1/-1 added exactly into an R32F target
//     (GL_ONE, GL_ONE blending).
//  3. Resolve (full screen, shadowvolume/ShadowVolumeResolve.glsl): visibility 1 where no volume contains
//     the point, the exact count, and the stencil's 8-bit count.
//
// Parameter: receiver_offset (fraction of the distance to the eye; orthographic: of the scene's radius): the
// visible point is taken that far toward the camera, so its own caster's near cap counts as behind it.
// Buffers: depth_complexity_center (the count of caster triangles crossed by the segment from the point to
// the light's centre, the point moved by receiver_offset), stencil_count (the same modulo 256, as the stencil
// holds it), volume_count_status (the count's self-check, a cut-short mark).
// Statistics (stats.json technique_statistics): silhouette_edges, boundary_edges, non_manifold_edges,
// inconsistent_edges, edges, edge_on_triangles, flipped_triangles, side_quads, near_caps, far_caps,
// volume_triangles, caster_triangles, collapsed_triangles, volume_build_ms (CPU).
// Object-space export: silhouettes (silhouettes.vtp, SilhouetteExport.h).
// Limits: alpha textures are not honoured (a perforated caster shadows as a solid; textured shadow volumes,
// Hasselgren & Akenine-Moeller 2007, are a later technique); the volume count is exact up to 2^24.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor shadowVolumeTechnique();

// shadow-volume's parameters, typed (parsed once, by from()).
struct ShadowVolumeSettings
{
  double receiverOffset{}; // of the eye distance

  static ShadowVolumeSettings from(const ParameterValues& values);
};

// The technique's probe (TechniqueDescriptor::probe): the crossing count of the segment from the pixel's point
// (moved by receiver_offset) to the light's centre (casterCrossings), each crossed caster triangle, the count
// as depth_complexity_center and stencil_count, and the visibility the resolve derives from it.
ProbeOutcome probeShadowVolume(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
