// The prefilter every filterable map shares (vsm's and esm's moments, MSM's power moments, CSM's Fourier basis): the
// separable box of `blurTexels` (moments/BoxBlur.glsl, x then y, clamp to edge), then, for prefilter = mipmap, the
// mip chain with trilinear filtering (survey §6). One implementation, so that every method averages the same texels
// its light_leak compares against (boxPcf in common/MomentLookup.glsl).
#pragma once

#include <vtkSmartPointer.h>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace sl
{

class FullScreenQuad;

// Returns `texture` box-blurred over blurTexels (a new texture; `texture` itself when blurTexels <= 1), mip-mapped
// when `mipmap`. `blurQuad` and `framebuffer` are the calling pass's (released with it).
vtkSmartPointer<vtkTextureObject> prefilterMoments(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  FullScreenQuad& blurQuad, vtkSmartPointer<vtkTextureObject> texture, int blurTexels, bool mipmap);

} // namespace sl
