// The `ss08` technique's pass (techniques/ss08/Ss08Technique.h): four full-screen draws, Fig. 3 of Schwarz and
// Stamminger 2008: the search and raw LOQ map (ss08/shaders/Ss08Loq.glsl), the LOQ map's separable smoothing in
// x then y (Ss08LoqSmoothing.glsl), and the blended back-projection (Ss08Visibility.glsl), whose first eight
// outputs are fragment outputs and the rest image stores. Structures (the min-max pyramid, the microrects) are
// bound by their structures (lightspace/).
#pragma once

#include "passes/FullScreenQuad.h"
#include "techniques/vtkSLTechniquePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

class vtkSLSs08Pass : public vtkSLTechniquePass
{
public:
  static vtkSLSs08Pass* New();
  vtkTypeMacro(vtkSLSs08Pass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  // Table 2's columns (percentage of back-projecting pixels, mean and standard deviation of the micro-occluders
  // they examine), the blend overhead against floor(l) alone and against ceil(l) alone (§8), the mean
  // level and the pixels smoothing pushed below their budget's level.
  std::map<std::string, double> CollectStatistics() override;

protected:
  vtkSLSs08Pass();
  ~vtkSLSs08Pass() override;
  std::string GetFragmentShaderPath() const override { return "ss08/Ss08Visibility.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLSs08Pass(const vtkSLSs08Pass&) = delete;
  void operator=(const vtkSLSs08Pass&) = delete;

  // Builds (or reuses) `quad`'s program from `shaderPath` with the technique's preamble, binds the common and
  // technique uniforms, and returns the textures to deactivate after drawing.
  std::vector<vtkTextureObject*> Ready(vtkOpenGLRenderWindow* window, sl::FullScreenQuad& quad,
    const std::string& shaderPath, const std::string& label, vtkShaderProgram*& program);
  void EnsureTargets(vtkOpenGLRenderWindow* window, int width, int height);

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad LoqQuad;
  sl::FullScreenQuad SmoothingQuad;
  sl::FullScreenQuad VisibilityQuad;
  // RG32F: (l, LoqState) after the search, after smoothing in x, after smoothing in y.
  vtkSmartPointer<vtkTextureObject> LoqRawTarget;
  vtkSmartPointer<vtkTextureObject> LoqSmoothedXTarget;
  vtkSmartPointer<vtkTextureObject> LoqSmoothedTarget;
  vtkSmartPointer<vtkTextureObject> BudgetMapTexture; // budget_map=image: R32F at the frame's size
};
