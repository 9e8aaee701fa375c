// Shadow-map lookups shared by every shadow-map technique. Mirrors src/lightspace/ShadowMapMath.cpp line
// for line (tests compare the two on read-back buffers).
// Conventions: texel (i, j) spans [i, i+1) x [j, j+1) in uvTexels; depthLin is the distance along the
// light axis; a receiver is lit by a texel when (depthLin - bias) <= stored depthLin.
// Bias parameters param_bias_constant_texels, param_bias_slope_texels, param_bias_max_slope are declared
// by the technique's generated preamble.
uniform sampler2D shadowMapLinear;
uniform mat4 lightViewFromWorld;
uniform mat4 lightClipFromWorld;
uniform int shadowMapSize;
uniform int lightIsPerspective;
uniform vec4 lightDepthToClip;  // clip.z = -x d + y, clip.w = -z d + w for linear depth d
uniform float shadowTexelExtent; // texel size in window units (tangent for perspective, world for ortho)
uniform int lightWarped;         // 1: lightClipFromWorld holds a perspective warp (survey §4.2)
#if defined(SHADOW_MAP_POLYGON_ID) && SHADOW_MAP_POLYGON_ID
// depth_layer = polygon_id (Hourcade & Nicolas 1985, survey §5): the nearest caster triangle's id per texel and the
// triangle each pixel sees (scene triangle index + 1; 0: none).
uniform usampler2D shadowMapPolygonId;
uniform usampler2D receiverPolygonId;
#endif

// xy = uvTexels, z = depthLin
vec3 projectToShadowMap(vec3 pWs)
{
  vec4 clip = lightClipFromWorld * vec4(pWs, 1.0);
  vec2 ndc = clip.xy / clip.w;
  float depthLin = -(lightViewFromWorld * vec4(pWs, 1.0)).z;
  return vec3((ndc * 0.5 + 0.5) * float(shadowMapSize), depthLin);
}

float tanAngleToLight(vec3 nWs, vec3 toLight)
{
  float cosTheta = clamp(dot(nWs, toLight), 1e-4, 1.0);
  return sqrt(max(0.0, 1.0 - cosTheta * cosTheta)) / cosTheta;
}

float texelWorldSize(float depthLin)
{
  return lightIsPerspective != 0 ? shadowTexelExtent * depthLin : shadowTexelExtent;
}

// Survey §5: constant + slope-scaled bias, in texel-footprint units (see ShadowMapMath.h).
float depthBias(float tanTheta, float depthLin)
{
  return texelWorldSize(depthLin) *
    (param_bias_constant_texels + param_bias_slope_texels * min(tanTheta, param_bias_max_slope));
}

// d(texel u, v) / d(world position) at pWs for u = N (ndc.xy / 2 + 1/2), ndc = (M p).xy / (M p).w:
// N/2 (M_i - ndc_i M_w) / w (texelGradients, ShadowMapMath.cpp). Any light matrix, a warped one included.
void texelGradients(vec3 pWs, out vec3 gradU, out vec3 gradV)
{
  mat4 m = lightClipFromWorld;
  vec4 clip = m * vec4(pWs, 1.0);
  vec2 ndc = clip.xy / clip.w;
  vec3 rowX = vec3(m[0][0], m[1][0], m[2][0]);
  vec3 rowY = vec3(m[0][1], m[1][1], m[2][1]);
  vec3 rowW = vec3(m[0][3], m[1][3], m[2][3]);
  float scale = 0.5 * float(shadowMapSize) / clip.w;
  gradU = scale * (rowX - ndc.x * rowW);
  gradV = scale * (rowY - ndc.y * rowW);
}

// The world size of one texel at the receiver, the warped texel's footprint under a warp (receiverTexelWorldSize,
// ShadowMapMath.cpp): J = d(texel u, v) / d(light x, y), the larger column of J^-1.
float receiverTexelWorldSize(vec3 pWs, float depthLin)
{
  if (lightWarped == 0)
  {
    return texelWorldSize(depthLin);
  }
  vec3 gradU;
  vec3 gradV;
  texelGradients(pWs, gradU, gradV);
  vec3 lightX = vec3(lightViewFromWorld[0][0], lightViewFromWorld[1][0], lightViewFromWorld[2][0]);
  vec3 lightY = vec3(lightViewFromWorld[0][1], lightViewFromWorld[1][1], lightViewFromWorld[2][1]);
  float j00 = dot(gradU, lightX);
  float j01 = dot(gradU, lightY);
  float j10 = dot(gradV, lightX);
  float j11 = dot(gradV, lightY);
  float determinant = max(abs(j00 * j11 - j01 * j10), 1e-30);
  return max(sqrt(j11 * j11 + j10 * j10), sqrt(j01 * j01 + j00 * j00)) / determinant;
}

// depthBias with receiverTexelWorldSize (depthBiasAt, ShadowMapMath.cpp).
float depthBiasAt(float tanTheta, vec3 pWs, float depthLin)
{
  return receiverTexelWorldSize(pWs, depthLin) *
    (param_bias_constant_texels + param_bias_slope_texels * min(tanTheta, param_bias_max_slope));
}

ivec2 shadowMapTexel(vec2 uvTexels)
{
  return clamp(ivec2(floor(uvTexels)), ivec2(0), ivec2(shadowMapSize - 1));
}

float storedDepth(vec2 uvTexels)
{
  return texelFetch(shadowMapLinear, shadowMapTexel(uvTexels), 0).r;
}

// 1 = lit, 0 = shadowed, for one texel.
float shadowTest(vec2 uvTexels, float comparisonDepthLin)
{
  return comparisonDepthLin <= storedDepth(uvTexels) ? 1.0 : 0.0;
}

// The depth the map's depth buffer stores for linear depth `depthLin`: window z in [0, 1] (hyperbolic for a
// perspective light); 0 for any depth before the near plane. CPU twin: LightView::windowDepth.
float windowDepth(float depthLin)
{
  float clipZ = -lightDepthToClip.x * depthLin + lightDepthToClip.y;
  float clipW = -lightDepthToClip.z * depthLin + lightDepthToClip.w;
  return clipW > 0.0 ? max(0.5 * clipZ / clipW + 0.5, 0.0) : 0.0; // at or behind the light's centre: before near
}
