// Reading the G-buffer in full-screen passes (layout documented in src/passes/FrameResources.h).
uniform sampler2D gbufferPosition;
uniform sampler2D gbufferNormal;

struct Surface
{
  bool covered;
  bool receivesShadows;
  vec3 pWs;
  vec3 nWs;
};

Surface readSurface(ivec2 pixel)
{
  vec4 position = texelFetch(gbufferPosition, pixel, 0);
  vec4 normal = texelFetch(gbufferNormal, pixel, 0);
  Surface surface;
  surface.covered = position.w > 0.5;
  surface.receivesShadows = normal.w > 0.5;
  surface.pWs = position.xyz;
  surface.nWs = normal.xyz;
  return surface;
}
