// The `yfgl09` technique's pass: yfgl09/shaders/Yfgl09Visibility.glsl drawn twice, first one fragment per
// packet (image stores into the technique targets, the packet's class into a packet-sized target), then one
// fragment per pixel for the packets not computed packet-wise (Alg. 1 steps 5-8). Needs the dual-grid MSSM
// (passes/vtkSLHsmPass).
#pragma once

#include "passes/FullScreenQuad.h"
#include "techniques/vtkSLTechniquePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

class vtkOpenGLFramebufferObject;
class vtkTextureObject;

class vtkSLYfgl09Pass : public vtkSLTechniquePass
{
public:
  static vtkSLYfgl09Pass* New();
  vtkTypeMacro(vtkSLYfgl09Pass, vtkSLTechniquePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  // From the packet target (the last sub-light's with sub-lights): packets by class and the percentage of
  // coherent packets among the non-trivial ones (§6: 52 / 68 / 88 % for light sizes 40 / 80 / 160).
  std::map<std::string, double> CollectStatistics() override;

protected:
  vtkSLYfgl09Pass();
  ~vtkSLYfgl09Pass() override;
  std::string GetFragmentShaderPath() const override { return "yfgl09/Yfgl09Visibility.glsl"; }
  std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram* program) override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLYfgl09Pass(const vtkSLYfgl09Pass&) = delete;
  void operator=(const vtkSLYfgl09Pass&) = delete;

  // Draws one of the two passes; returns after the textures it bound are released.
  void DrawPass(vtkOpenGLRenderWindow* window, sl::FullScreenQuad& quad, bool packetPass);

  vtkNew<vtkOpenGLFramebufferObject> PacketFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> PixelFramebuffer;
  sl::FullScreenQuad PacketQuad;
  sl::FullScreenQuad PixelQuad;
  vtkSmartPointer<vtkTextureObject> PacketTarget; // RGBA32F per packet: class, Eq. 2, P_d, visited nodes per pixel
};
