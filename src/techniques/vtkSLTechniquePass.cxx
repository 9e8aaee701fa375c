#include "techniques/vtkSLTechniquePass.h"

#include "core/Error.h"
#include "structures/LightSpaceStructure.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "passes/ScopedRenderTarget.h"

#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cctype>

namespace
{

std::string upperCase(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
  return text;
}

} // namespace

vtkSLTechniquePass::vtkSLTechniquePass() = default;
vtkSLTechniquePass::~vtkSLTechniquePass() = default;

std::vector<std::string> vtkSLTechniquePass::OutputNames(const sl::TechniqueDescriptor& descriptor)
{
  return descriptor.outputNames();
}

sl::ShaderDefines vtkSLTechniquePass::TechniqueDefines() const
{
  const sl::FrameResources& frame = *this->Frame;
  sl::ShaderDefines defines = sl::commonDefines();
  const std::vector<std::string> outputs = OutputNames(*frame.technique);
  for (std::size_t location = 0; location < outputs.size(); ++location)
  {
    defines.push_back({ "OUT_" + upperCase(outputs[location]), std::to_string(location) });
  }
  // Category codes of categorical buffers, `<BUFFER>_<IDENTIFIER> code`, and the technique's shared constants:
  // written once in C++ (the CPU mirror's enum or constexpr), never copied into a shader.
  for (const sl::BufferSpec& buffer : frame.technique->buffers)
  {
    for (std::size_t code = 0; code < buffer.categoryIdentifiers.size(); ++code)
    {
      defines.push_back({ upperCase(buffer.name + "_" + buffer.categoryIdentifiers[code]), std::to_string(code) });
    }
  }
  for (const sl::ShaderConstant& constant : frame.technique->shaderConstants)
  {
    defines.push_back({ constant.name, std::to_string(constant.value) });
  }
  for (const sl::ParameterSpec& spec : frame.technique->parameters)
  {
    if (spec.choices.empty())
    {
      continue;
    }
    for (std::size_t i = 0; i < spec.choices.size(); ++i)
    {
      defines.push_back({ upperCase(spec.name + "_" + spec.choices[i]), std::to_string(i) });
    }
    defines.push_back({ upperCase(spec.name), std::to_string(frame.parameters.getInt(spec.name)) });
  }
  // The defines each light-space structure's GLSL lookup needs (e.g. the min-max layout of common/HsmLayout.glsl).
  for (const sl::LightSpaceStructure* structure : sl::withBuildDependencies(frame.technique->structuresFor(frame.parameters)))
  {
    const sl::ShaderDefines structureDefines = structure->shaderDefines(frame);
    defines.insert(defines.end(), structureDefines.begin(), structureDefines.end());
  }
  const sl::ShaderDefines extra = this->GetExtraDefines();
  defines.insert(defines.end(), extra.begin(), extra.end());
  return defines;
}

std::string vtkSLTechniquePass::ParameterDeclarations() const
{
  std::string declarations;
  for (const sl::ParameterSpec& spec : this->Frame->technique->parameters)
  {
    if (spec.choices.empty() && !spec.file)
    {
      declarations += "uniform float param_" + spec.name + ";\n";
    }
  }
  return declarations;
}

std::vector<vtkTextureObject*> vtkSLTechniquePass::SetCommonUniforms(vtkShaderProgram* program)
{
  const sl::FrameResources& frame = *this->Frame;
  std::vector<vtkTextureObject*> bound;
  bound.push_back(sl::bindTexture(program, "gbufferPosition", frame.gbufferPosition));
  bound.push_back(sl::bindTexture(program, "gbufferNormal", frame.gbufferNormal));
  sl::setLightUniforms(program, *frame.light);
  if (program->IsUniformUsed("cameraNearOrigin"))
  {
    sl::setCameraRayUniforms(program, frame.camera);
  }
  // Every light-space structure the frame built for the technique (those it lists and what they are built from),
  // bound the way its folder says (lightspace/*/).
  for (const sl::LightSpaceStructure* structure : sl::withBuildDependencies(frame.technique->structuresFor(frame.parameters)))
  {
    const std::vector<vtkTextureObject*> textures = structure->bind(program, frame);
    bound.insert(bound.end(), textures.begin(), textures.end());
  }
  for (const sl::ParameterSpec& spec : frame.technique->parameters)
  {
    if (spec.choices.empty() && !spec.file)
    {
      sl::setFloatIfUsed(program, ("param_" + spec.name).c_str(), frame.parameters.get(spec.name));
    }
  }
  return bound;
}

std::vector<vtkTextureObject*> vtkSLTechniquePass::TechniqueTargets() const
{
  std::vector<vtkTextureObject*> targets;
  for (const std::string& output : this->Frame->technique->outputNames())
  {
    targets.push_back(this->Frame->techniqueTargets.at(output));
  }
  return targets;
}

void vtkSLTechniquePass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const sl::ScopedRenderTarget target(window, this->Framebuffer, this->TechniqueTargets());
  const std::string fragmentSource =
    sl::assembleShader(this->GetFragmentShaderPath(), this->TechniqueDefines(), this->ParameterDeclarations());
  vtkShaderProgram* program = this->Quad.ready(window, fragmentSource, frame.technique->name);

  std::vector<vtkTextureObject*> bound = this->SetCommonUniforms(program);
  const std::vector<vtkTextureObject*> extra = this->SetTechniqueUniforms(program);
  bound.insert(bound.end(), extra.begin(), extra.end());

  this->Quad.render();
  this->AfterDraw();
  for (vtkTextureObject* texture : bound)
  {
    texture->Deactivate();
  }
}

void vtkSLTechniquePass::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.releaseGraphicsResources(window);
  this->Framebuffer->ReleaseGraphicsResources(window);
}

void vtkSLTechniquePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FragmentShader: " << (this->Frame ? this->GetFragmentShaderPath() : std::string("(none)")) << "\n";
}
