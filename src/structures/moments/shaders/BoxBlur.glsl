// One direction of a separable box filter of BLUR_WIDTH texels (odd or even: taps at offsets
// -(w - 1)/2 .. (w - 1)/2, texel centres, clamp to edge). Two passes (x then y) give the w x w box the
// moment techniques filter with (prefilter = blur).
uniform sampler2D source;
uniform ivec2 direction; // (1, 0) or (0, 1)
uniform int blurWidth;

layout(location = 0) out vec4 outFiltered;

void main()
{
  ivec2 size = textureSize(source, 0);
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  int first = -(blurWidth - 1) / 2;
  for (int k = 0; k < blurWidth; ++k)
  {
    sum += texelFetch(source, clamp(pixel + (first + k) * direction, ivec2(0), size - 1), 0);
  }
  outFiltered = sum / float(blurWidth);
}
