// Final image: Lambertian shading by the technique's visibility, plus a small ambient term so shadowed
// surfaces stay readable. Output is sRGB-encoded 8-bit. Multisampled frames (MSAA_SAMPLES defined): each sample is
// shaded with its own surface and its resolved visibility (passes/vtkSLMsaaResolvePass.h) and the linear radiances
// are averaged, the ordinary MSAA resolve (Schwarz and Stamminger 2008 §7 apply visibility "to the multisampled
// colour buffer with a custom resolve", §7).
#include "common/GBufferInputs.glsl"
#include "common/LightModel.glsl"

uniform sampler2D gbufferAlbedoDepth;
uniform sampler2D visibilityTexture;
uniform float lightIntensity;
uniform vec3 backgroundColor;
#ifdef MSAA_SAMPLES
uniform sampler2DMS multisamplePosition;
uniform sampler2DMS multisampleNormal;
uniform sampler2DMS multisampleAlbedoDepth;
uniform sampler2D sampleVisibility;
#endif

layout(location = 0) out vec4 outColor;

const float ambient = 0.12;
const float displayGamma = 2.2;

vec3 linearRadiance(vec3 albedo, vec3 pWs, vec3 nWs, float visibility)
{
  float cosine = max(0.0, dot(nWs, directionToLight(pWs)));
  return albedo * (ambient + (1.0 - ambient) * lightIntensity * visibility * cosine);
}

void main()
{
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#ifdef MSAA_SAMPLES
  vec4 visibilities = texelFetch(sampleVisibility, pixel, 0);
  vec3 sum = vec3(0.0);
  for (int s = 0; s < MSAA_SAMPLES; ++s)
  {
    vec4 position = texelFetch(multisamplePosition, pixel, s);
    if (position.w <= 0.5)
    {
      sum += pow(backgroundColor, vec3(displayGamma));
      continue;
    }
    vec3 nWs = texelFetch(multisampleNormal, pixel, s).xyz;
    vec3 albedo = texelFetch(multisampleAlbedoDepth, pixel, s).rgb;
    sum += clamp(linearRadiance(albedo, position.xyz, nWs, visibilities[s]), 0.0, 1.0);
  }
  outColor = vec4(pow(sum / float(MSAA_SAMPLES), vec3(1.0 / displayGamma)), 1.0);
#else
  Surface surface = readSurface(pixel);
  if (!surface.covered)
  {
    outColor = vec4(backgroundColor, 1.0);
    return;
  }
  vec3 albedo = texelFetch(gbufferAlbedoDepth, pixel, 0).rgb;
  float visibility = texelFetch(visibilityTexture, pixel, 0).r;
  vec3 radiance = linearRadiance(albedo, surface.pWs, surface.nWs, visibility);
  outColor = vec4(pow(clamp(radiance, 0.0, 1.0), vec3(1.0 / displayGamma)), 1.0);
#endif
}
