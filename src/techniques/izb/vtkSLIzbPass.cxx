#include "techniques/izb/vtkSLIzbPass.h"

#include "core/Error.h"
#include "gl/ComputeProgram.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "techniques/izb/IzbTechnique.h"
#include "techniques/izb/IzbTwin.h"

#include <vtkObjectFactory.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace sl
{

namespace
{

constexpr std::size_t izbNodeWords = 8;  // IzbNode: vec4 + 4 uints (std430)
constexpr std::size_t izbPixelWords = 8; // two uvec4 per pixel (IzbCommon.glsl)

// A buffer of `words` 32-bit words, reallocated when the frame needs another size.
void izbEnsureBuffer(std::unique_ptr<StorageBuffer>& buffer, std::size_t words)
{
  if (!buffer || buffer->words() != words)
  {
    buffer = std::make_unique<StorageBuffer>(words);
  }
}

// The grid and light uniforms of izb/IzbCommon.glsl and common/LightModel.glsl.
void izbSetGridUniforms(const ComputeProgram& program, const IzbGrid& grid, const Light& light)
{
  program.setInt("izbDirectional", grid.directional ? 1 : 0);
  program.setInt("izbGridSize", grid.size);
  program.setVector("izbLightPosition", grid.lightPosition);
  program.setVector("izbLightDirection", grid.lightDirection);
  program.setVector("izbAxisU", grid.axisU);
  program.setVector("izbAxisV", grid.axisV);
  program.setVectors("izbWindow", { glm::dvec4(grid.windowMin, grid.texelsPerUnit) });
  program.setFloat("izbRoundoff", izbFloatRoundoff);
  program.setInt("lightType", lightTypeCode(light.type));
  program.setVector("lightCenterWs", light.center);
  program.setVector("lightNormalWs", light.normal);
  program.setVector("lightDirectionWs", light.direction);
  program.setFloat("lightCosCone", std::cos(glm::radians(light.coneAngleDeg)));
}

// Storage bindings 0-7 (the pass's buffers) back to none, as the other passes leave their image units.
void izbUnbindStorage()
{
  for (GLuint binding = 0; binding <= 7; ++binding)
  {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, 0);
  }
}

} // namespace
} // namespace sl

vtkStandardNewMacro(vtkSLIzbPass);

vtkSLIzbPass::vtkSLIzbPass() = default;
vtkSLIzbPass::~vtkSLIzbPass() = default;

const sl::ComputeProgram& vtkSLIzbPass::Program(const std::string& path)
{
  const std::string source = sl::assembleShader(path, this->TechniqueDefines());
  std::unique_ptr<sl::ComputeProgram>& program = this->Programs[source];
  if (!program)
  {
    program = std::make_unique<sl::ComputeProgram>(source, path);
  }
  return *program;
}

void vtkSLIzbPass::Execute(const vtkRenderState* state)
{
  const sl::FrameResources& frame = *this->Frame;
  const sl::IzbSettings settings = sl::IzbSettings::from(frame.parameters);
  const sl::IzbGrid grid = sl::IzbGrid::fit(*frame.light, frame.scene->bounds(), settings.gridSize);
  const int width = frame.width();
  const int height = frame.height();
  const std::size_t pixelCount = static_cast<std::size_t>(width) * height;
  const std::size_t nodeCount = std::min<std::size_t>(static_cast<std::size_t>(settings.nodeBudget), pixelCount);
  sl::izbEnsureBuffer(this->Heads, grid.texelCount());
  sl::izbEnsureBuffer(this->Counts, grid.texelCount());
  sl::izbEnsureBuffer(this->Nodes, nodeCount * sl::izbNodeWords);
  sl::izbEnsureBuffer(this->Pixels, pixelCount * sl::izbPixelWords);
  sl::izbEnsureBuffer(this->Counter, 1);
  this->Heads->clear();
  this->Counts->clear();
  this->Counter->clear();

  // Step 1: every visible sample into its texel's list.
  const sl::ComputeProgram& bin = this->Program("izb/IzbBin.glsl");
  bin.use();
  sl::izbSetGridUniforms(bin, grid, *frame.light);
  frame.gbufferPosition->Activate();
  frame.gbufferNormal->Activate();
  bin.setInt("gbufferPosition", frame.gbufferPosition->GetTextureUnit());
  bin.setInt("gbufferNormal", frame.gbufferNormal->GetTextureUnit());
  bin.setInt("nodeBudget", static_cast<int>(nodeCount));
  bin.setInt("listBudget", settings.listBudget);
  bin.setFloat("normalOffset", settings.offsetWorld(*frame.scene));
  bin.setInt("imageWidth", width);
  bin.setInt("imageHeight", height);
  this->Heads->bind(0);
  this->Counts->bind(1);
  this->Nodes->bind(2);
  this->Pixels->bind(3);
  this->Counter->bind(4);
  bin.dispatch({ (width + 7) / 8, (height + 7) / 8 });
  frame.gbufferPosition->Deactivate();
  frame.gbufferNormal->Deactivate();
  sl::checkGlErrors("izb (binning)");

  // Step 2: the (triangle, texel) pairs whose texel lists a sample, from each triangle's conservative cover.
  const auto coverStart = std::chrono::steady_clock::now();
  const std::vector<std::uint32_t> counts = this->Counts->download();
  const std::vector<glm::dvec3> triangles = sl::izbCasterTriangles(*frame.scene);
  std::vector<std::uint32_t> texels;
  std::vector<std::uint32_t> pairs;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    texels.clear();
    grid.triangleTexels(triangles[t], triangles[t + 1], triangles[t + 2],
      [&counts](std::uint32_t texel) { return counts[texel] > 0; }, texels);
    for (const std::uint32_t texel : texels)
    {
      pairs.push_back(static_cast<std::uint32_t>(t / 3));
      pairs.push_back(texel);
    }
  }
  const double coverMilliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - coverStart).count();
  const std::size_t pairCount = pairs.size() / 2;
  if (pairCount > static_cast<std::size_t>(std::numeric_limits<int>::max() / 2))
  {
    throw sl::GraphicsError("izb: " + std::to_string(pairCount) +
      " (triangle, texel) pairs exceed what one dispatch indexes; lower grid_size");
  }

  // Step 3: each pair's samples against its triangle.
  if (pairCount > 0)
  {
    std::vector<glm::vec4> vertices;
    vertices.reserve(triangles.size());
    for (const glm::dvec3& vertex : triangles)
    {
      vertices.emplace_back(glm::vec3(vertex), 0.0f);
    }
    sl::izbEnsureBuffer(this->Triangles, vertices.size() * sizeof(glm::vec4) / sizeof(std::uint32_t));
    this->Triangles->upload(vertices.data(), vertices.size() * sizeof(glm::vec4));
    const std::vector<std::uint32_t> vertexIds = sl::izbCasterVertexIds(*frame.scene);
    sl::izbEnsureBuffer(this->VertexIds, vertexIds.size());
    this->VertexIds->upload(vertexIds);
    sl::izbEnsureBuffer(this->Pairs, pairs.size());
    this->Pairs->upload(pairs);
    const sl::ComputeProgram& test = this->Program("izb/IzbTest.glsl");
    test.use();
    sl::izbSetGridUniforms(test, grid, *frame.light);
    const std::size_t groups = (pairCount + 63) / 64;
    const int groupsX = static_cast<int>(std::min<std::size_t>(groups, 65535));
    const int groupsY = static_cast<int>((groups + groupsX - 1) / groupsX);
    test.setInt("pairCount", static_cast<int>(pairCount));
    test.setInt("groupsX", groupsX);
    test.setInt("listBudget", settings.listBudget);
    test.setFloat("normalOffset", settings.offsetWorld(*frame.scene));
    this->Heads->bind(0);
    this->Nodes->bind(2);
    this->Pixels->bind(3);
    this->Triangles->bind(5);
    this->Pairs->bind(6);
    this->VertexIds->bind(7);
    test.dispatch({ groupsX, groupsY });
    sl::checkGlErrors("izb (triangle tests)");
  }
  glUseProgram(0);

  std::size_t occupied = 0;
  std::uint32_t longest = 0;
  for (const std::uint32_t count : counts)
  {
    occupied += count > 0 ? 1 : 0;
    longest = std::max(longest, count);
  }
  this->Statistics = {
    { "izb_triangles", static_cast<double>(triangles.size() / 3) },
    { "izb_pairs", static_cast<double>(pairCount) },
    { "izb_occupied_texels", static_cast<double>(occupied) },
    { "izb_grid_texels", static_cast<double>(grid.texelCount()) },
    { "izb_max_list_length", static_cast<double>(longest) },
    { "izb_cover_ms", coverMilliseconds },
  };

  // Step 4: the resolve, the base class's full-screen shader (SetTechniqueUniforms binds 1 and 3 again).
  this->Superclass::Execute(state);
  sl::izbUnbindStorage();
}

std::vector<vtkTextureObject*> vtkSLIzbPass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  this->Counts->bind(1);
  this->Pixels->bind(3);
  program->SetUniformi("imageWidth", this->Frame->width());
  return {};
}

std::map<std::string, double> vtkSLIzbPass::CollectStatistics()
{
  std::map<std::string, double> statistics = this->Statistics;
  if (!this->Pixels || !this->Frame)
  {
    return statistics;
  }
  const std::size_t pixelCount = static_cast<std::size_t>(this->Frame->width()) * this->Frame->height();
  const std::vector<std::uint32_t> state = this->Pixels->download();
  SL_CHECK(state.size() == sl::izbPixelWords * pixelCount);
  double samples = 0.0, ambiguous = 0.0, cutShort = 0.0, paired = 0.0;
  for (std::size_t pixel = 0; pixel < pixelCount; ++pixel)
  {
    const std::uint32_t* words = &state[sl::izbPixelWords * pixel];
    const std::uint32_t flags = words[0];
    samples += (flags & sl::IzbFlagTested) ? 1.0 : 0.0;
    cutShort += (flags & sl::IzbFlagCutShort) ? 1.0 : 0.0;
    const bool pairCovers = sl::izbEdgePairCovers(words[3], words[4], words[5]);
    const bool uncertain = (flags & sl::IzbFlagUncertain) && !(flags & sl::IzbFlagDefinite) && !pairCovers;
    paired += (pairCovers && !(flags & sl::IzbFlagDefinite)) ? 1.0 : 0.0;
    ambiguous += ((flags & sl::IzbFlagAmbiguousPlacement) || uncertain) ? 1.0 : 0.0;
  }
  statistics["izb_samples"] = samples;
  statistics["izb_ambiguous_pixels"] = ambiguous;
  statistics["izb_cut_short_pixels"] = cutShort;
  statistics["izb_shared_edge_pixels"] = paired;
  statistics["izb_nodes"] = std::min<double>(this->Counter->download()[0], this->Nodes->words() / sl::izbNodeWords);
  return statistics;
}

void vtkSLIzbPass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Programs.clear();
  this->Heads.reset();
  this->Counts.reset();
  this->Nodes.reset();
  this->Pixels.reset();
  this->Counter.reset();
  this->Triangles.reset();
  this->Pairs.reset();
  this->VertexIds.reset();
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLIzbPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Programs: " << this->Programs.size() << "\n";
}
