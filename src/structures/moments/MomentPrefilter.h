// The prefilter every filterable map shares (vsm's and esm's moments, MSM's power moments, CSM's Fourier basis): the
// separable box of `blurTexels` (moments/BoxBlur.glsl, x then y, clamp to edge), then, for prefilter = mipmap, the
// mip chain with trilinear filtering (survey §6). One implementation, so that every method averages the same texels
// its light_leak compares against (boxPcf in common/MomentLookup.glsl).
#pragma once

#include "gl/ComputeProgram.h"
#include "structures/moments/ReceiverTiles.h"

#include <vtkSmartPointer.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

namespace sl
{

class FullScreenQuad;
struct FrameResources;

class StorageBuffer;

// The render targets a pass keeps from frame to frame (and sub-light to sub-light) while the map's size and format
// hold: a fresh 2048^2 RGBA32F target costs llvmpipe ~50 ms to allocate (src/structures/moments/README.md).
struct PrefilterTargets
{
  vtkSmartPointer<vtkTextureObject> horizontal;
  vtkSmartPointer<vtkTextureObject> blurred;
  // The sparse blur's program (shaders/SparseMomentsBlur.glsl, sparseMomentsOfDepth).
  std::unique_ptr<ComputeProgram> sparseProgram;
};

// The moment map's sparse blur straight from the shadow map (`region.sparse`): each listed texel's box of moments
// formed inline as shaders/MomentsFromDepth.glsl forms them (shaders/MomentsOfDepth.glsl), so the moments pass is
// skipped; the result equals prefilterMoments of that pass's output on the listed texels. Returns targets.blurred.
vtkSmartPointer<vtkTextureObject> sparseMomentsOfDepth(vtkOpenGLRenderWindow* window, vtkTextureObject* shadowMapLinear,
  double depthNear, double depthFar, double esmExponent, int blurTexels, const PrefilterRegion& region,
  PrefilterTargets& targets);
// The blur at the listed texels of a sparse `region` only, written into `targets` (RGBA32F, image units 0 ..
// targets.size() - 1, as many as the shader's SPARSE_BLUR_IMAGES) by `program`: a shader built on
// shaders/SparseBoxBlur.glsl whose momentsOfDepth uniforms are set; it reads `source` (the shadow map's linear depth).
void blurReceiverTexels(ComputeProgram& program, vtkTextureObject* source,
  const std::vector<vtkTextureObject*>& targets, int blurTexels, const PrefilterRegion& region);
// The work groups of a dispatch with one invocation per listed item (a texel, or a pixel's footprint of four): 64
// invocations a group, in rows of at most 1024 groups (a dispatch's x count is capped); the shader numbers its item
// gl_GlobalInvocationID.y * rowWidth + .x.
glm::ivec2 listedTexelGroups(int listedItems);
// `slot` itself when it is a float target of that size and components in `window`, else a new one put in `slot`;
// with nearest filtering (a mip-mapped prefilter of an earlier frame sets trilinear).
vtkTextureObject* reusedFloatTarget(vtkOpenGLRenderWindow* window, vtkSmartPointer<vtkTextureObject>& slot, int width,
  int height, int components);

// Returns `texture` box-blurred over blurTexels (a texture of `targets` when given, else a new one; `texture` itself
// when blurTexels <= 1), mip-mapped when `mipmap`. `blurQuad` and `framebuffer` are the calling pass's (released
// with it). With a `region` (not sparse: that one is sparseMomentsOfDepth's), each blur pass draws only its
// rectangles (the other texels are left as they were: nobody reads them).
vtkSmartPointer<vtkTextureObject> prefilterMoments(vtkOpenGLRenderWindow* window, vtkOpenGLFramebufferObject* framebuffer,
  FullScreenQuad& blurQuad, vtkSmartPointer<vtkTextureObject> texture, int blurTexels, bool mipmap,
  const PrefilterRegion* region = nullptr, PrefilterTargets* targets = nullptr);

// Draws `quad` (its program ready, its target bound) over each of `rects` with the scissor; over the whole target
// when `rects` is null.
void renderQuadOver(vtkOpenGLRenderWindow* window, FullScreenQuad& quad, const std::vector<TileRect>* rects);

// The tiles of the frame's light-space map (frame.lightView) that its receivers read: the G-buffer's receivers
// projected into the map on the GPU (shaders/ReceiverTiles.glsl), the flags read back. Holds its compute program.
class ReceiverTileMarker
{
public:
  ReceiverTileMarker();
  ~ReceiverTileMarker();
  // The tiles, and with `listTexels` in `readTexels` the listed texels (empty when there were more than the list
  // holds).
  ReceiverTiles mark(
    const FrameResources& frame, int tileTexels, bool listTexels, std::vector<std::uint32_t>& readTexels);
  // The plan of a prefilter of blurTexels over the receivers' tiles (ReceiverTiles::tileTexelsFor the map), after
  // which VTK's shader cache binds its next program itself (the compute program is left bound behind it).
  ReceiverPrefilterPlan plan(vtkOpenGLRenderWindow* window, const FrameResources& frame, int blurTexels);
  // That plan where prefilter_region = receivers (`receiversOnly`) and marking can pay (receiverRegionCanPay for the
  // frame's pixels), else none: the whole map.
  std::optional<ReceiverPrefilterPlan> planWhereItPays(
    vtkOpenGLRenderWindow* window, const FrameResources& frame, int blurTexels, bool receiversOnly);
  void release();

private:
  std::unique_ptr<ComputeProgram> program_;
  std::unique_ptr<StorageBuffer> readTexels_; // kept for the point draws (PrefilterRegion::readTexelBuffer)
};

} // namespace sl
