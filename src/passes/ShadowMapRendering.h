// Rendering one shadow map for a fitted light view: the casters' linear depth (R32F, cleared to 2 x far so
// empty texels never shadow) and hardware depth (D32F). Shared by the shadow_map stage and by techniques
// that render several maps per frame (reference-sm).
#pragma once

#include "gl/GlResources.h"
#include "lightspace/LightView.h"

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace sl
{

// secondDepth: keep only faces turned away from the light (second-depth shadow maps, survey §5).
void renderShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, bool secondDepth, vtkTextureObject* linearDepth,
  vtkTextureObject* hardwareDepth);
// The same as renderShadowMap (front and back faces) with, in `polygonIds` (R32UI), the nearest triangle's id
// (MeshDrawer's meshTriangleBase + gl_PrimitiveID + 1; 0 where no caster): polygon-id shadow maps (survey §5).
void renderPolygonIdShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, vtkTextureObject* linearDepth, vtkTextureObject* hardwareDepth,
  vtkTextureObject* polygonIds);
// Depth peeling (Everitt 2001), the second layer of midpoint and dual shadow maps (survey §5): the same casters, all
// faces, keeping at each texel the nearest depth strictly behind `firstLayer`'s (a map renderShadowMap rendered).
void renderPeeledShadowMap(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer, MeshDrawer& drawer,
  const GpuScene& scene, const LightView& view, vtkTextureObject* firstLayer, vtkTextureObject* linearDepth,
  vtkTextureObject* hardwareDepth);

} // namespace sl
