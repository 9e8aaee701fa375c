// The per-pixel preamble of the back-projection methods (gbp06, gbp07, yfgl09): the GLSL mirror of
// sl::prepareContourReceiver (src/techniques/ContourReceiver.cpp). The kernel of Eq. 1 (Yang et
// al. 2009) with the map's near plane, shrunk param_kernel_refinements times to the minimum depth inside it
// (MSSM kernels, Schwarz and Stamminger 2007), and lit / umbra from the min-max structure's range over the
// kernel's samples plus one ring (Alg. 1 step 5). Sets the receiver plane (setReceiverPlane) as a side effect.
// Needs common/SoftShadowKernels.glsl, common/HsmLookup.glsl, the parameter kernel_refinements and the decision
// codes KERNEL_LIT, KERNEL_UMBRA, KERNEL_PENUMBRA (generated: sl::contourKernelShaderConstants, the
// BackprojectionClass codes of the CPU mirror's ContourReceiver::classification).

struct ContourKernel
{
  ivec2 lo;     // kernel texels
  ivec2 hi;
  ivec2 ringLo; // plus one ring, clamped to the map
  ivec2 ringHi;
  vec2 comparison; // the receiver's comparison depths over the ring
  float kernelTexels; // 2 max(half extent)
  int decision; // KERNEL_PENUMBRA, KERNEL_LIT or KERNEL_UMBRA
};

void ringed(ivec2 lo, ivec2 hi, out ivec2 ringLo, out ivec2 ringHi)
{
  ringLo = max(lo - 1, ivec2(0));
  ringHi = min(hi + 1, ivec2(shadowMapSize - 1));
}

// (min, max) depth over the samples [lo, hi] from whichever min-max structure the technique built.
vec2 kernelSampleRange(ivec2 lo, ivec2 hi)
{
#if HSM_LAYOUT == HSM_LAYOUT_DUAL
  return mssmSampleRange(lo, hi);
#else
  return hsmRange(lo, hi);
#endif
}

// For a receiver that needs a shadow test.
ContourKernel prepareContourKernel(ShadowReceiver receiver)
{
  ContourKernel kernel;
  float d = receiver.depthLin;
  vec2 uv = receiver.uvTexels;
  setReceiverPlane(receiver.pWs, receiver.nWs);
  vec2 halfTexels = kernelHalfTexels(d, lightNearDepth);
  kernelRectangle(uv, halfTexels, kernel.lo, kernel.hi);
  ringed(kernel.lo, kernel.hi, kernel.ringLo, kernel.ringHi);
  vec2 depthRange = kernelSampleRange(kernel.ringLo, kernel.ringHi);
  for (int refinement = 0; refinement < int(param_kernel_refinements); ++refinement)
  {
    halfTexels = kernelHalfTexels(d, clamp(depthRange.x, lightNearDepth, d));
    kernelRectangle(uv, halfTexels, kernel.lo, kernel.hi);
    ringed(kernel.lo, kernel.hi, kernel.ringLo, kernel.ringHi);
    depthRange = kernelSampleRange(kernel.ringLo, kernel.ringHi);
  }
  kernel.kernelTexels = 2.0 * max(halfTexels.x, halfTexels.y);
  kernel.comparison = comparisonDepthRange(kernel.ringLo, kernel.ringHi, d, receiver.bias);
  // Umbra only when the ring lies inside the map: beyond it the contour methods see non-occluders.
  bool ringInsideMap = kernel.ringLo == kernel.lo - 1 && kernel.ringHi == kernel.hi + 1;
  kernel.decision = depthRange.x >= kernel.comparison.y ? KERNEL_LIT
    : ringInsideMap && depthRange.y < kernel.comparison.x ? KERNEL_UMBRA : KERNEL_PENUMBRA;
  return kernel;
}
