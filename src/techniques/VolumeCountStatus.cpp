#include "techniques/VolumeCountStatus.h"

namespace sl
{

BufferSpec volumeCountStatusBuffer()
{
  BufferSpec spec = categoricalBuffer("volume_count_status",
    "the shadow volumes' count checked against itself (vtkSLShadowVolumePass.h): inconsistent marks a pixel whose "
    "depth_complexity_center is below 0, or whose volume faces along the camera ray do not sum to the eye's count",
    volumeCountCategories);
  // Decided when the pass reads the count back, not by the resolves: dcs's resolve already writes the 8 outputs
  // llvmpipe allows.
  spec.fromPass = true;
  return spec;
}

} // namespace sl
