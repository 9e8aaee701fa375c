// Multi-view shadow maps (Yang et al. 2009 §5): after the technique ran for sub-light k of S x S, adds its
// buffer into the frame's combined one: visibility (and continuous buffers) averaged, accumulated += v / S^2;
// work counters summed, accumulated += v; categorical buffers kept from the first sub-light (weight 0 after
// it), except that a later sub-light's cut-short code (BufferSpec::cutShortCode) replaces it, so that a pixel
// cut short under any sub-light stays flagged. The first sub-light overwrites, so the combined targets need
// no clearing.
// Driver: src/passes/vtkSLSubLightAccumulatePass.cxx.
layout(local_size_x = 8, local_size_y = 8) in;

layout(r32f, binding = 0) uniform readonly image2D subLightBuffer;
layout(r32f, binding = 1) uniform image2D combinedBuffer;
uniform int imageWidth;
uniform int imageHeight;
uniform float weight;
uniform int firstSubLight; // 1 for sub-light 0
uniform float cutShortCode; // categorical buffers: the code that marks a cut-short pixel, or -1

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= imageWidth || pixel.y >= imageHeight)
  {
    return;
  }
  float value = imageLoad(subLightBuffer, pixel).r;
  if (firstSubLight == 1)
  {
    imageStore(combinedBuffer, pixel, vec4(weight == 0.0 ? value : weight * value));
  }
  else if (weight != 0.0)
  {
    imageStore(combinedBuffer, pixel, vec4(imageLoad(combinedBuffer, pixel).r + weight * value));
  }
  else if (cutShortCode >= 0.0 && value == cutShortCode)
  {
    imageStore(combinedBuffer, pixel, vec4(value));
  }
}
