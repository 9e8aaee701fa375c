// The visible receivers summarised on the GPU for the light-frustum fit (see lightspace/LightView.h):
// shaders/lightspace/FocusReduction.glsl reduces the G-buffer in one dispatch per question and only its
// nine result words are read back. ImageReceivers is the CPU reference it is tested against.
#pragma once

#include "gl/ComputeProgram.h"
#include "lightspace/LightView.h"

#include <map>
#include <memory>
#include <string>

class vtkTextureObject;

namespace sl
{

class GpuReceivers : public ReceiverSource
{
public:
  GpuReceivers();
  ~GpuReceivers() override;
  // The G-buffer to reduce for the next summary()/extent() calls.
  void setGBuffer(vtkTextureObject* gbufferPosition, vtkTextureObject* gbufferNormal);

  ReceiverSummary summary(const Light& light) override;
  ReceiverExtent extent(const Light& light, const LightView& view, const glm::dvec3& axis) override;

private:
  // `query`: the bytes of every other uniform the program reads (the extent's view), for the memo.
  std::vector<std::uint32_t> run(const ComputeProgram& program, const Light& light, const std::string& query);

  std::unique_ptr<ComputeProgram> summaryProgram_;
  std::unique_ptr<ComputeProgram> extentProgram_;
  StorageBuffer result_;
  vtkTextureObject* position_ = nullptr;
  vtkTextureObject* normal_ = nullptr;
  // The reductions of this G-buffer so far, by their inputs: shadow_map_size = auto fits the view twice (at the
  // largest size, then at the chosen one) and the receivers do not depend on the size. Cleared by setGBuffer.
  std::map<std::string, std::vector<std::uint32_t>> reductions_;
};

// Inverse of the shader's orderedBits(): the float whose order-preserving encoding is `bits`.
float floatFromOrderedBits(std::uint32_t bits);

} // namespace sl
