// G-buffer: world position, normal and albedo of the nearest surface per pixel.
in vec3 pWsIn;
in vec3 nWsIn;
in vec2 uvIn;

uniform mat4 clipFromWorld;
uniform mat4 viewFromWorld;

out vec3 pWs;
out vec3 nWs;
out vec2 uv;
out float viewDepth;

void main()
{
  pWs = pWsIn;
  nWs = nWsIn;
  uv = uvIn;
  viewDepth = -(viewFromWorld * vec4(pWsIn, 1.0)).z;
  gl_Position = clipFromWorld * vec4(pWsIn, 1.0);
}
