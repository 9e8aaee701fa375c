// The shadow map's depth histogram for layer_placement=gaps (LayeredMoments.h, layeredGapEnds): every texel's linear
// depth counted into LAYERED_HISTOGRAM_BINS equal bins over [near, far] with atomics; the empty texels (2 far) and
// depths before near are not counted. CPU mirror: layeredHistogramBin / layeredDepthHistogram.
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D shadowMapLinear;
uniform int mapSize;
uniform float depthNear;
uniform float depthFar;
layout(std430, binding = 0) buffer LayeredHistogram
{
  uint layeredHistogram[];
};

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, ivec2(mapSize))))
  {
    return;
  }
  float depth = texelFetch(shadowMapLinear, texel, 0).r;
  if (!(depth <= depthFar) || depth < depthNear)
  {
    return;
  }
  float position = (depth - depthNear) / (depthFar - depthNear) * float(LAYERED_HISTOGRAM_BINS);
  atomicAdd(layeredHistogram[clamp(int(floor(position)), 0, LAYERED_HISTOGRAM_BINS - 1)], 1u);
}
