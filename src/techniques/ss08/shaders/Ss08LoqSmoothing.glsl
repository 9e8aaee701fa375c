// ss08, passes 2 and 3 of 4 (Schwarz & Stamminger 2008, Fig. 3 step 2; §4.2, §8): one direction of
// the separable LOQ-map smoothing, "a variant of separable bilateral filtering where the smoothing kernel stops
// at depth discontinuities and at the interface to regions where no backprojection is required". Support
// 11 x 11 (§8): from the pixel, up to 5 neighbours each way are averaged (box weights, the project's
// reading), the run stopping before the first neighbour that is not smoothed (LOQ_STATE_SMOOTHED) or whose
// camera depth differs from the previous one's by more than param_smoothing_depth_threshold times the smaller
// of the two. Pixels not smoothed keep their level. The second pass (finalPass) applies LOQ_FLOOR: with `raw`,
// smoothing never lowers l below l_raw (so ceil(l) keeps the budget).
// CPU mirror: src/techniques/ss08/Ss08Technique.cpp (ss08SmoothLoq).
uniform sampler2D loqInput;          // RG: level, LOQ_STATE_*
uniform sampler2D loqRaw;            // the LOQ pass's output (final pass: the floor)
uniform sampler2D gbufferAlbedoDepth; // a: camera depth
uniform ivec2 smoothingStep;         // (1, 0) or (0, 1)
uniform int finalPass;

layout(location = 0) out vec2 outLoq;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(loqInput, 0);
  vec2 centre = texelFetch(loqInput, pixel, 0).xy;
  outLoq = centre;
  if (int(centre.y) != LOQ_STATE_SMOOTHED)
  {
    return;
  }
  float centreDepth = texelFetch(gbufferAlbedoDepth, pixel, 0).a;
  float sum = centre.x;
  float count = 1.0;
  for (int side = -1; side <= 1; side += 2)
  {
    float previousDepth = centreDepth;
    for (int k = 1; k <= LOQ_SMOOTHING_RADIUS; ++k)
    {
      ivec2 neighbour = pixel + side * k * smoothingStep;
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size)))
      {
        break;
      }
      vec2 value = texelFetch(loqInput, neighbour, 0).xy;
      float depth = texelFetch(gbufferAlbedoDepth, neighbour, 0).a;
      if (int(value.y) != LOQ_STATE_SMOOTHED ||
        abs(depth - previousDepth) > param_smoothing_depth_threshold * min(depth, previousDepth))
      {
        break;
      }
      sum += value.x;
      count += 1.0;
      previousDepth = depth;
    }
  }
  float level = sum / count;
#if LOQ_FLOOR == LOQ_FLOOR_RAW
  if (finalPass != 0)
  {
    level = max(level, texelFetch(loqRaw, pixel, 0).x);
  }
#endif
  outLoq = vec2(level, centre.y);
}
