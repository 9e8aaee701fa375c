// Vertex shader of a blur pass drawn as points (ReceiverTiles.h, ReceiverPrefilterPlan): one point per texel the
// receivers read (the vertical pass; pointsPerTexel = 1), or per texel of the column of blurWidth texels the vertical
// pass reads around it (the horizontal pass; pointsPerTexel = blurWidth, rows y + first .. y + first + w - 1 clamped
// to the map as BoxBlur.glsl clamps). Each point covers one texel centre, where BoxBlur.glsl computes exactly what the
// full-screen draw computes there. The list is shaders/ReceiverTiles.glsl's: word 0 the count, then x | y << 16.
layout(std430, binding = 0) readonly buffer ReceiverReadTexels
{
  uint receiverReadTexels[];
};
uniform int pointsPerTexel;
uniform int firstOffset; // -(blurWidth - 1) / 2
uniform int mapSize;

void main()
{
  int entry = gl_VertexID / pointsPerTexel;
  int k = gl_VertexID - entry * pointsPerTexel;
  uint packedTexel = receiverReadTexels[1 + entry];
  ivec2 texel = ivec2(int(packedTexel & 0xFFFFu), int(packedTexel >> 16));
  if (pointsPerTexel > 1)
  {
    texel.y = clamp(texel.y + firstOffset + k, 0, mapSize - 1);
  }
  gl_Position = vec4((vec2(texel) + 0.5) / float(mapSize) * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = 1.0;
}
