// The PCF over the texel rectangle [lo, hi] (every texel up to param_max_grid_taps per axis, a regular sub-grid
// beyond), each tap compared as PCSS's filter step compares it (the bias and, with receiver_plane_bias, the
// receiver's tangent plane), not at the receiver's own depth: unbiased, a receiver sloped in depth fails against its
// own texels and light_leak would be the bound minus self-shadowing. The light_leak reference of the SAT-based soft
// techniques (savsm, msmsoft). Needs shadowTest and tapComparisonDepth (common/ShadowMapCommon.glsl,
// common/SoftShadowKernels.glsl). CPU mirror: rectanglePcf
// (techniques/MomentReference.h).
float pcfOverRectangle(ivec2 lo, ivec2 hi, float d, float bias)
{
  // Its own origin, step and count, not KernelGrid: that type comes only with a blocker search (msmsoft has none).
  vec2 origin;
  vec2 step;
  ivec2 count;
  for (int axis = 0; axis < 2; ++axis)
  {
    int texels = hi[axis] - lo[axis] + 1;
    if (texels <= int(param_max_grid_taps))
    {
      origin[axis] = float(lo[axis]) + 0.5;
      step[axis] = 1.0;
      count[axis] = texels;
    }
    else
    {
      count[axis] = int(param_max_grid_taps);
      step[axis] = float(texels) / param_max_grid_taps;
      origin[axis] = float(lo[axis]) + 0.5 * step[axis];
    }
  }
  float lit = 0.0;
  for (int j = 0; j < count.y; ++j)
  {
    for (int i = 0; i < count.x; ++i)
    {
      vec2 tap = origin + vec2(i, j) * step;
      lit += shadowTest(tap, tapComparisonDepth(tap, d, bias));
    }
  }
  return lit / float(count.x * count.y);
}
