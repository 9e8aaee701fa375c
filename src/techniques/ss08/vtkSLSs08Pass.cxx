#include "techniques/ss08/vtkSLSs08Pass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/ss08/Ss08Technique.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkSLSs08Pass);

namespace
{
constexpr std::size_t fragmentOutputCount = 8; // IMAGE_OUTPUT_FIRST
}

vtkSLSs08Pass::vtkSLSs08Pass() = default;
vtkSLSs08Pass::~vtkSLSs08Pass() = default;

std::vector<vtkTextureObject*> vtkSLSs08Pass::SetTechniqueUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  sl::setSoftShadowUniforms(program, frame);
  sl::setIntIfUsed(program, "ss08TopLevel", sl::hsmLevelCount(frame.lightView.resolution));
  const int size[2] = { frame.width(), frame.height() };
  if (program->IsUniformUsed("imageSize"))
  {
    program->SetUniform2i("imageSize", size);
  }
  if (program->IsUniformUsed("bitmaskSampleX"))
  {
    // accumulation=bitmask: the samples by column (x of rows 4q..4q+3 of column i at [4 i + q]) and by row (y of
    // columns 4q..4q+3 of row j at [4 j + q]), so that a boundary column or row is tested with four vec4 compares
    // (Ss08Visibility.glsl). Multiples of 2^-16 below 1: exact in float.
    const std::vector<glm::dvec2>& points = sl::ss08BitmaskSamples().basePoints();
    constexpr int side = sl::ss08BitmaskGridSide;
    float byColumn[side * side / 4][4];
    float byRow[side * side / 4][4];
    for (int a = 0; a < side; ++a)
    {
      for (int b = 0; b < side; ++b)
      {
        byColumn[4 * a + b / 4][b % 4] = static_cast<float>(points[static_cast<std::size_t>(b * side + a)].x);
        byRow[4 * a + b / 4][b % 4] = static_cast<float>(points[static_cast<std::size_t>(a * side + b)].y);
      }
    }
    program->SetUniform4fv("bitmaskSampleX", side * side / 4, byColumn);
    program->SetUniform4fv("bitmaskSampleY", side * side / 4, byRow);
  }
  std::vector<vtkTextureObject*> bound;
  if (this->BudgetMapTexture && program->IsUniformUsed("budgetMapTexture"))
  {
    bound.push_back(sl::bindTexture(program, "budgetMapTexture", this->BudgetMapTexture));
  }
  return bound;
}

std::vector<vtkTextureObject*> vtkSLSs08Pass::Ready(vtkOpenGLRenderWindow* window, sl::FullScreenQuad& quad,
  const std::string& shaderPath, const std::string& label, vtkShaderProgram*& program)
{
  const std::string source = sl::assembleShader(shaderPath, this->TechniqueDefines(), this->ParameterDeclarations());
  program = quad.ready(window, source, this->Frame->technique->name + " (" + label + ")");
  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  const std::vector<vtkTextureObject*> extra = this->SetTechniqueUniforms(program);
  bound.insert(bound.end(), extra.begin(), extra.end());
  return bound;
}

void vtkSLSs08Pass::EnsureTargets(vtkOpenGLRenderWindow* window, int width, int height)
{
  const auto fits = [&](const vtkSmartPointer<vtkTextureObject>& target) {
    return target && target->GetContext() == window && static_cast<int>(target->GetWidth()) == width &&
      static_cast<int>(target->GetHeight()) == height;
  };
  for (vtkSmartPointer<vtkTextureObject>* target : { &this->LoqRawTarget, &this->LoqSmoothedXTarget, &this->LoqSmoothedTarget })
  {
    if (!fits(*target))
    {
      *target = sl::makeFloatTarget(window, width, height, 2);
    }
  }
}

void vtkSLSs08Pass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const int width = frame.width();
  const int height = frame.height();
  this->EnsureTargets(window, width, height);
  // A forced level above the map's top would be clamped by the shader while stats.json kept the requested one.
  const int topLevel = sl::hsmLevelCount(frame.lightView.resolution);
  const sl::Ss08Settings settings = sl::Ss08Settings::from(frame.parameters);
  if (const int forced = settings.forceLevel; forced > topLevel)
  {
    throw sl::InputError(sl::format("ss08: --set force_level=", forced, ": a ", frame.lightView.resolution, "^2 shadow map has levels 0 to ",
      topLevel, " (level ", topLevel, " is one texel for the whole map)"));
  }
  this->BudgetMapTexture = nullptr;
  if (settings.budgetMap == sl::Ss08BudgetMap::Image)
  {
    const sl::ImageF budgets = sl::ss08BudgetImage(settings, width, height);
    auto texture = vtkSmartPointer<vtkTextureObject>::New();
    texture->SetContext(window);
    texture->SetMinificationFilter(vtkTextureObject::Nearest);
    texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    if (!texture->Create2DFromRaw(width, height, 1, VTK_FLOAT, const_cast<float*>(budgets.data.data())))
    {
      throw sl::GraphicsError("ss08: cannot upload the budget image");
    }
    this->BudgetMapTexture = texture;
  }
  const auto release = [](const std::vector<vtkTextureObject*>& bound) {
    for (vtkTextureObject* texture : bound)
    {
      texture->Deactivate();
    }
  };
  vtkShaderProgram* program = nullptr;

  // 1. The search and the raw LOQ map.
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, { this->LoqRawTarget });
    const std::vector<vtkTextureObject*> bound = this->Ready(window, this->LoqQuad, "ss08/Ss08Loq.glsl", "LOQ map", program);
    this->LoqQuad.render();
    release(bound);
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);

  // 2-3. Smoothing, x then y (none with loq_smoothing=off: the raw map is read).
  vtkTextureObject* loqMap = this->LoqRawTarget;
  if (settings.loqSmoothing)
  {
    const vtkTextureObject* inputs[2] = { this->LoqRawTarget, this->LoqSmoothedXTarget };
    vtkTextureObject* outputs[2] = { this->LoqSmoothedXTarget, this->LoqSmoothedTarget };
    for (int pass = 0; pass < 2; ++pass)
    {
      const sl::ScopedRenderTarget target(window, this->Framebuffer, { outputs[pass] });
      const std::string source = sl::assembleShader("ss08/Ss08LoqSmoothing.glsl", this->TechniqueDefines(), this->ParameterDeclarations());
      program = this->SmoothingQuad.ready(window, source, frame.technique->name + " (LOQ smoothing)");
      std::vector<vtkTextureObject*> bound;
      bound.push_back(sl::bindTexture(program, "loqInput", const_cast<vtkTextureObject*>(inputs[pass])));
      bound.push_back(sl::bindTexture(program, "loqRaw", this->LoqRawTarget));
      bound.push_back(sl::bindTexture(program, "gbufferAlbedoDepth", frame.gbufferAlbedoDepth));
      sl::setFloatIfUsed(program, "param_smoothing_depth_threshold", settings.smoothingDepthThreshold);
      const int step[2] = { pass == 0 ? 1 : 0, pass == 0 ? 0 : 1 };
      program->SetUniform2i("smoothingStep", step);
      sl::setIntIfUsed(program, "finalPass", pass);
      this->SmoothingQuad.render();
      release(bound);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }
    loqMap = this->LoqSmoothedTarget;
  }

  // 4. Visibility: eight fragment outputs, the rest image stores.
  const std::vector<vtkTextureObject*> targets = this->TechniqueTargets();
  const std::vector<vtkTextureObject*> fragmentTargets(targets.begin(),
    targets.begin() + static_cast<std::ptrdiff_t>(std::min(fragmentOutputCount, targets.size())));
  {
    const sl::ScopedRenderTarget target(window, this->Framebuffer, fragmentTargets);
    for (std::size_t k = fragmentOutputCount; k < targets.size(); ++k)
    {
      glBindImageTexture(static_cast<GLuint>(k - fragmentOutputCount), targets[k]->GetHandle(), 0, GL_FALSE, 0,
        GL_WRITE_ONLY, GL_R32F);
    }
    std::vector<vtkTextureObject*> bound =
      this->Ready(window, this->VisibilityQuad, this->GetFragmentShaderPath(), "visibility", program);
    bound.push_back(sl::bindTexture(program, "loqSmoothed", loqMap));
    this->VisibilityQuad.render();
    release(bound);
    for (std::size_t k = fragmentOutputCount; k < targets.size(); ++k)
    {
      glBindImageTexture(static_cast<GLuint>(k - fragmentOutputCount), 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }
  }
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

std::map<std::string, double> vtkSLSs08Pass::CollectStatistics()
{
  const sl::FrameResources& frame = *this->Frame;
  const auto read = [&](const char* name) { return sl::readFloatTexture(frame.techniqueTargets.at(name), 1); };
  const sl::ImageF classes = read("classification");
  const sl::ImageF counts = read("micro_occluders");
  const sl::ImageF floorCounts = read("micro_occluders_floor");
  const sl::ImageF ceilCounts = read("micro_occluders_ceil");
  const sl::ImageF levels = read("loq");
  const sl::ImageF violations = read("loq_budget_violation");
  double tested = 0.0;
  double backProjecting = 0.0;
  double sum = 0.0;
  double sumSquares = 0.0;
  double floorSum = 0.0;
  double ceilSum = 0.0;
  double levelSum = 0.0;
  double violating = 0.0;
  for (std::size_t i = 0; i < classes.pixelCount(); ++i)
  {
    const int code = static_cast<int>(classes.data[i]);
    if (code == static_cast<int>(sl::Ss08Class::NotTested))
    {
      continue;
    }
    ++tested;
    // Back-projecting pixels are those that examined micro-occluders' slots (penumbra, growth penumbra with
    // growth=on, cut short).
    if (floorCounts.data[i] <= 0.0f)
    {
      continue;
    }
    ++backProjecting;
    sum += counts.data[i];
    sumSquares += static_cast<double>(counts.data[i]) * counts.data[i];
    floorSum += floorCounts.data[i];
    ceilSum += ceilCounts.data[i];
    levelSum += levels.data[i];
    violating += violations.data[i] > 0.0f ? 1.0 : 0.0;
  }
  const double mean = backProjecting > 0.0 ? sum / backProjecting : 0.0;
  const double variance = backProjecting > 0.0 ? std::max(sumSquares / backProjecting - mean * mean, 0.0) : 0.0;
  return {
    { "backprojecting_pixels_percent", tested > 0.0 ? 100.0 * backProjecting / tested : 0.0 },
    { "micro_occluders_mean", mean },
    { "micro_occluders_stdev", std::sqrt(variance) },
    { "blend_overhead_vs_floor_level", floorSum > 0.0 ? sum / floorSum : 0.0 },
    { "blend_overhead_vs_ceil_level", ceilSum > 0.0 ? sum / ceilSum : 0.0 },
    { "mean_loq", backProjecting > 0.0 ? levelSum / backProjecting : 0.0 },
    { "budget_violation_pixels", violating },
  };
}

void vtkSLSs08Pass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->LoqQuad.releaseGraphicsResources(window);
  this->SmoothingQuad.releaseGraphicsResources(window);
  this->VisibilityQuad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->LoqRawTarget = nullptr;
  this->LoqSmoothedXTarget = nullptr;
  this->LoqSmoothedTarget = nullptr;
  this->BudgetMapTexture = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLSs08Pass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LoqMapAllocated: " << (this->LoqRawTarget != nullptr) << "\n";
}
