// Stage 3: a technique's visibility pass. It writes "visibility" and every buffer its descriptor
// publishes into FrameResources::techniqueTargets (R32F each, allocated by the pipeline).
//
// This base class implements the common case, a full-screen fragment shader over the G-buffer:
//  - outputs: one `layout(location = OUT_<BUFFER>)` per target, locations generated from the descriptor;
//  - variants: each enumeration parameter P with choices c_i becomes `#define P i` plus
//    `#define P_C_i i` (upper case), so shaders write `#if FILTER == FILTER_HARDWARE_BILINEAR`;
//  - numeric parameters become `uniform float param_<name>;`, declared and set automatically;
//  - the G-buffer, light, camera (texel ratio) and shadow-map uniforms of shaders/common are set.
// A technique subclass names its fragment shader and may add uniforms or defines. Techniques that are not
// a full-screen shader (the `vtk` technique) override Execute() instead.
#pragma once

#include "gl/ShaderLibrary.h"
#include "frame/FrameResult.h"
#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"
#include "frame/TechniqueDescriptor.h"

#include <vtkNew.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkShaderProgram;
class vtkTextureObject;

class vtkSLTechniquePass : public vtkSLStagePass
{
public:
  vtkTypeMacro(vtkSLTechniquePass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "technique"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

  // Names of the targets in output-location order: "visibility", then the descriptor's buffers.
  static std::vector<std::string> OutputNames(const sl::TechniqueDescriptor& descriptor);
  // Whole-frame counts a technique reports besides its buffers (stats.json "technique_statistics", bench
  // columns), read after the frame's timings with the frame's resources still bound; none by default.
  virtual std::map<std::string, double> CollectStatistics() { return {}; }
  // Geometry an object-space technique exports (written as <name>.vtp), read like CollectStatistics; none by
  // default.
  virtual std::vector<sl::NamedPolyData> CollectObjectSpaceExports() { return {}; }
  // The descriptor's buffers marked fromPass (any number of components), read back by the pass itself, read like
  // CollectStatistics; every such buffer must be returned (the pipeline checks).
  virtual std::vector<sl::NamedImage> CollectPassBuffers() { return {}; }

protected:
  vtkSLTechniquePass();
  ~vtkSLTechniquePass() override;
  void Execute(const vtkRenderState* state) override;

  virtual std::string GetFragmentShaderPath() const = 0;
  virtual sl::ShaderDefines GetExtraDefines() const { return {}; }
  // The other fragment shaders the pass assembles with TechniqueDefines() (e.g. dcs's wedge and STSV passes): the
  // path and the flags it adds, one program each. tests/unit/ShaderContractTest.cpp checks that they keep no copy
  // of a generated number either.
  struct PassShader
  {
    std::string path;
    std::vector<std::string> flags;
  };
  virtual std::vector<PassShader> GetPassShaders() const { return {}; }
  // Called with the program bound, after the common uniforms; returns textures to deactivate afterwards.
  virtual std::vector<vtkTextureObject*> SetTechniqueUniforms(vtkShaderProgram*) { return {}; }
  // Called after drawing (restore sampler bindings and the like).
  virtual void AfterDraw() {}

  sl::ShaderDefines TechniqueDefines() const;
  std::string ParameterDeclarations() const;
  // Binds the G-buffer and (when fitted) the frame's shadow map, and sets the light, camera, shadow-map and
  // parameter uniforms of shaders/common for `program`; returns the textures to deactivate after drawing.
  std::vector<vtkTextureObject*> SetCommonUniforms(vtkShaderProgram* program);
  // The frame's targets for "visibility" and the descriptor's buffers, in output-location order.
  std::vector<vtkTextureObject*> TechniqueTargets() const;

private:
  vtkSLTechniquePass(const vtkSLTechniquePass&) = delete;
  void operator=(const vtkSLTechniquePass&) = delete;

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::FullScreenQuad Quad;
};
