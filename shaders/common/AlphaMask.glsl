// Perforated (alpha-textured) surfaces: where alpha < 0.5 there is no surface at all, so the fragment is
// discarded in every geometry pass (G-buffer and light depth). The texture is sampled nearest, repeat
// wrap, at the triangle's interpolated uv; the CPU reference and the ray tracer sample it the same way.
uniform int hasAlphaTexture;
uniform sampler2D alphaTexture;

bool isPerforated(vec2 uv)
{
  return hasAlphaTexture != 0 && texture(alphaTexture, uv).r < 0.5;
}
