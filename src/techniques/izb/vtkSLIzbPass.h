// The `izb` technique's pass (IzbTechnique.h): the irregular z-buffer in three GPU steps and one CPU step.
//  1. izb/IzbBin.glsl (compute, one invocation per pixel): each visible sample into its light texel's list.
//  2. CPU: the per-texel sample counts are read back; every caster triangle's conservative cover
//     (IzbGrid::triangleTexels, double precision) is walked and each (triangle, texel) pair whose texel lists a sample
//     is kept.
//  3. izb/IzbTest.glsl (compute, one invocation per pair): the texel's samples tested against the triangle.
//  4. izb/IzbResolve.glsl (the base class's full-screen pass): visibility and the buffers.
//
// Why linked lists (a head pointer per texel, a node per sample from one atomic counter) rather than a counting pass,
// a prefix sum and a fill: the prefix sum over the grid (up to 6 x 2048^2 texels) would need a multi-pass scan on
// the GPU to keep each invocation under llvmpipe's 65535 loop iterations, and the lists need none of it; a sample's
// tests are a set membership (an atomicOr of bits), so the lists' nondeterministic order changes no result. The
// per-texel count the list needs anyway (list_budget) is the same atomicAdd a counting pass would do.
//
// Why the cover on the CPU (step 2) rather than a geometry shader widening each triangle by half a texel diagonal:
// the widened triangle's edges are computed in float and rasterised with llvmpipe's 1/256-pixel snapping, so its
// conservativeness would rest on rounding arguments about the rasteriser; clipped and walked in double, with a margin
// far above the GPU's placement error (which the pass bounds and flags per sample), it holds by construction, and the
// CPU twin uses the very same function. The cost is one read-back of the counts and O(cover) CPU work per frame
// (izb_cover_ms in stats.json).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

#include <map>
#include <memory>
#include <string>

namespace sl
{
class ComputeProgram;
class StorageBuffer;
}

class vtkSLIzbPass : public vtkSLTechniquePass
{
public:
  static vtkSLIzbPass* New();
  vtkTypeMacro(vtkSLIzbPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  std::map<std::string, double> CollectStatistics() override;

protected:
  vtkSLIzbPass();
  ~vtkSLIzbPass() override;
  void Execute(const vtkRenderState* state) override;
  std::string GetFragmentShaderPath() const override { return "izb/IzbResolve.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;

private:
  vtkSLIzbPass(const vtkSLIzbPass&) = delete;
  void operator=(const vtkSLIzbPass&) = delete;

  const sl::ComputeProgram& Program(const std::string& path);

  std::map<std::string, std::unique_ptr<sl::ComputeProgram>> Programs; // by assembled source
  std::unique_ptr<sl::StorageBuffer> Heads, Counts, Nodes, Pixels, Counter, Triangles, Pairs, VertexIds;
  std::map<std::string, double> Statistics;
};
