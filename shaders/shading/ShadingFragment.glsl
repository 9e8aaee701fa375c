// Final image: Lambertian shading by the technique's visibility, plus a small ambient term so shadowed
// surfaces stay readable. Output is sRGB-encoded 8-bit.
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform sampler2D gbufferAlbedoDepth;
uniform sampler2D visibilityTexture;
uniform float lightIntensity;
uniform vec3 backgroundColor;

layout(location = 0) out vec4 outColor;

const float ambient = 0.12;

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  Surface surface = readSurface(pixel);
  if (!surface.covered)
  {
    outColor = vec4(backgroundColor, 1.0);
    return;
  }
  vec3 albedo = texelFetch(gbufferAlbedoDepth, pixel, 0).rgb;
  float visibility = texelFetch(visibilityTexture, pixel, 0).r;
  float cosine = max(0.0, dot(surface.nWs, directionToLight(surface.pWs)));
  vec3 radiance = albedo * (ambient + (1.0 - ambient) * lightIntensity * visibility * cosine);
  outColor = vec4(pow(clamp(radiance, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
