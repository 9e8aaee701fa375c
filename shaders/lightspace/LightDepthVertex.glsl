// Shadow map: depth of the nearest caster seen from the light.
in vec3 pWsIn;
in vec2 uvIn;

uniform mat4 lightClipFromWorld;
uniform mat4 lightViewFromWorld;

out vec2 uv;
out float depthLin;

void main()
{
  uv = uvIn;
  depthLin = -(lightViewFromWorld * vec4(pWsIn, 1.0)).z;
  gl_Position = lightClipFromWorld * vec4(pWsIn, 1.0);
}
