// Views that partition the pixels (survey §4.3, lightspace/PartitionViews.h): after the technique ran with view k's
// map, adds its buffer into the frame's combined one with the pixel's weight for view k, from the selection (primary,
// secondary, primary's weight): w = weight (k primary) + (1 - weight) (k secondary). A pixel that reads one view takes its value
// exactly (the other views' weight 0 adds nothing); categorical buffers take the primary view's value. View 0
// initialises every pixel, so the combined targets need no clearing.
// Driver: src/passes/vtkSLPartitionAccumulatePass.cxx.
layout(local_size_x = 8, local_size_y = 8) in;

layout(r32f, binding = 0) uniform readonly image2D viewBuffer;
layout(r32f, binding = 1) uniform image2D combinedBuffer;
layout(rgba32f, binding = 2) uniform readonly image2D viewSelection;
uniform int imageWidth;
uniform int imageHeight;
uniform int viewIndex;
uniform int categorical; // 1: the primary view's value, unblended

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= imageWidth || pixel.y >= imageHeight)
  {
    return;
  }
  vec4 selection = imageLoad(viewSelection, pixel);
  int primary = int(selection.x + 0.5);
  int secondary = int(selection.y + 0.5);
  float weight = (primary == viewIndex ? selection.z : 0.0) + (secondary == viewIndex ? 1.0 - selection.z : 0.0);
  if (categorical == 1)
  {
    weight = primary == viewIndex ? 1.0 : 0.0;
  }
  float combined = viewIndex == 0 ? 0.0 : imageLoad(combinedBuffer, pixel).r;
  if (weight > 0.0)
  {
    float value = imageLoad(viewBuffer, pixel).r;
    combined = categorical == 1 ? value : combined + weight * value;
  }
  if (viewIndex == 0 || weight > 0.0)
  {
    imageStore(combinedBuffer, pixel, vec4(combined));
  }
}
