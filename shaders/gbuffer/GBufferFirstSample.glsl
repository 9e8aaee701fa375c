// Multisampled G-buffer: sample 0 of each pixel into the single-sampled targets, depth included, so that every later
// pass reads the first sample as Schwarz and Stamminger 2008 §7 prescribe (s_z, "always the first", §7).
// Layout: src/passes/FrameResources.h.
uniform sampler2DMS multisamplePosition;
uniform sampler2DMS multisampleNormal;
uniform sampler2DMS multisampleAlbedoDepth;
uniform sampler2DMS multisampleDepth;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedoDepth;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outPosition = texelFetch(multisamplePosition, pixel, 0);
  outNormal = texelFetch(multisampleNormal, pixel, 0);
  outAlbedoDepth = texelFetch(multisampleAlbedoDepth, pixel, 0);
  // Uncovered: the cleared 1.0, which the depth test (less) leaves as cleared.
  gl_FragDepth = texelFetch(multisampleDepth, pixel, 0).r;
}
