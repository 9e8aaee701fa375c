// The shadow volumes' count checked against itself (vtkSLShadowVolumePass.h): the buffer volume_count_status of
// every technique that takes the light centre's count from the volumes (shadow-volume, dcs, penumbra-wedge).
#pragma once

#include "frame/TechniqueDescriptor.h"

namespace sl
{

// volume_count_status codes (vtkSLShadowVolumePass.h, VolumeCountStatusImage).
enum class VolumeCountStatus
{
  Consistent = 0,
  Inconsistent = 1
};

// The codes' categories, as the buffer and shadow-volume's probe label them.
inline const Category<VolumeCountStatus> volumeCountCategories[] = {
  { VolumeCountStatus::Consistent, "CONSISTENT", "volume count consistent" },
  { VolumeCountStatus::Inconsistent, "INCONSISTENT",
    "volume count inconsistent (below 0, or the faces along the ray miss the eye's count): not exact", true },
};

// The categorical buffer volume_count_status: the volume count checked against itself on the GPU (below 0, or the
// volume faces along the camera ray not summing to the eye's count: a face lost or doubled). Its inconsistent
// category is a cut-short mark (counted in cut_short_pixels). shadow-volume, dcs and penumbra-wedge, which all take
// the centre's count from these volumes, publish it.
BufferSpec volumeCountStatusBuffer();

} // namespace sl
