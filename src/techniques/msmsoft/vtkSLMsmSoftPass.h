// The `msmsoft` technique's pass: msmsoft/shaders/MsmSoftVisibility.glsl with the PCSS-family kernel uniforms and the
// light's depth range (the moment SAT is bound by its structure, structures/momentsat). The filter step's Hamburger
// 4MSM (support_depth_near, support_depth_far, hankel_pivot) does not fit the eight render targets beside the other
// buffers: the shader stores it into an RGBA32F image the pass reads back (CollectPassBuffers).
#pragma once

#include "techniques/vtkSLTechniquePass.h"

#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

class vtkSLMsmSoftPass : public vtkSLTechniquePass
{
public:
  static vtkSLMsmSoftPass* New();
  vtkTypeMacro(vtkSLMsmSoftPass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  std::vector<sl::NamedImage> CollectPassBuffers() override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLMsmSoftPass() = default;
  ~vtkSLMsmSoftPass() override = default;
  std::string GetFragmentShaderPath() const override { return "msmsoft/MsmSoftVisibility.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void AfterDraw() override;

private:
  vtkSLMsmSoftPass(const vtkSLMsmSoftPass&) = delete;
  void operator=(const vtkSLMsmSoftPass&) = delete;

  // (support_depth_near, support_depth_far, hankel_pivot, 0) per pixel, image unit 0 while drawing.
  vtkSmartPointer<vtkTextureObject> FilterSupport;
};
