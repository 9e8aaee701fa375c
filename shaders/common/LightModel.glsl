// The light, and which points it can reach at all (mirrors sl::lightCanReach, src/lightspace/LightView.cpp).
// SL_LIGHT_* constants come from the C++ preamble.
uniform int lightType;
uniform vec3 lightCenterWs;
uniform vec3 lightNormalWs;    // area / spot: toward the scene
uniform vec3 lightDirectionWs; // directional: direction the light travels
uniform float lightCosCone;    // spot

vec3 directionToLight(vec3 pWs)
{
  return lightType == SL_LIGHT_DIRECTIONAL ? -lightDirectionWs : normalize(lightCenterWs - pWs);
}

bool lightCanReach(vec3 pWs, vec3 nWs)
{
  if (dot(nWs, directionToLight(pWs)) <= 0.0)
  {
    return false; // the surface faces away: its own body hides the light
  }
  if (lightType == SL_LIGHT_AREA)
  {
    return dot(lightNormalWs, pWs - lightCenterWs) > 0.0; // one-sided emitter
  }
  if (lightType == SL_LIGHT_SPOT)
  {
    return dot(lightNormalWs, normalize(pWs - lightCenterWs)) > lightCosCone;
  }
  return true;
}
