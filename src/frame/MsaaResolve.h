// The CPU twin of the custom multisample resolve (Schwarz and Stamminger 2008 §7; shaders/msaa/MsaaResolve.glsl,
// passes/vtkSLMsaaResolvePass.h), in the shader's float arithmetic so that the two agree bit for bit on read-back
// buffers. Rule, per covered sample s of pixel p (sample depth d_s; covered where d_s != 0, msaa_sample_depth's
// convention):
//  - p's first sample covered and |d_s - s_z(p)| <= tau s_z(p): s takes p's visibility (§7);
//  - otherwise s is distinct and takes the visibility of whichever of p (when its first sample is covered) and its
//    4-neighbours -x, +x, -y, +y (inside the image, first sample covered) has the s_z closest to d_s, ties keeping
//    the first in that order (§7); it counts as interpolated when that is a neighbour. With no candidate: 0.
// visibility(p) = the mean of its covered samples' values where p's first sample is covered, else 0.
#pragma once

#include "core/Image.h"

namespace sl
{

struct MsaaResolveInputs
{
  const ImageF* pixelVisibility = nullptr; // 1 component: the technique's, evaluated at the first sample
  const ImageF* firstCoverage = nullptr;   // 1 component: > 0.5 where the first sample is covered
  const ImageF* firstDepth = nullptr;      // 1 component: s_z, the first sample's view depth
  const ImageF* sampleDepth = nullptr;     // one component per sample: view depth, 0 where uncovered
};

struct MsaaResolved
{
  ImageF visibility;          // 1 component
  ImageF sampleVisibility;    // one component per sample (0 where uncovered)
  ImageF distinctSamples;     // 1 component
  ImageF interpolatedSamples; // 1 component
};

MsaaResolved msaaResolve(const MsaaResolveInputs& inputs, double depthTolerance);

} // namespace sl
