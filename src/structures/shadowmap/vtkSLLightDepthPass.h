// Stage 2b (when the technique needs a shadow map): renders the casters' linear and hardware depth from
// the light view the focus stage fitted. Parameters it reads: caster_faces (first- or second-depth) and depth_layer
// (midpoint or dual: two peeled layers combined into the map, survey §5).
#pragma once

#include "passes/FullScreenQuad.h"
#include "passes/vtkSLStagePass.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
namespace sl
{
struct ShadowMapSettings;
}

class vtkSLLightDepthPass : public vtkSLStagePass
{
public:
  static vtkSLLightDepthPass* New();
  vtkTypeMacro(vtkSLLightDepthPass, vtkSLStagePass);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  const char* GetStageName() const override { return "shadow_map"; }
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSLLightDepthPass();
  ~vtkSLLightDepthPass() override;
  void Execute(const vtkRenderState* state) override;

private:
  vtkSLLightDepthPass(const vtkSLLightDepthPass&) = delete;
  void operator=(const vtkSLLightDepthPass&) = delete;
  // depth_layer = midpoint or dual: both layers into the frame's ShadowMapLayersData, their combination into the map.
  void RenderDepthLayers(vtkOpenGLRenderWindow* window, const sl::ShadowMapSettings& settings, std::size_t index);
  // depth_layer = polygon_id: the map with its triangle ids, and the camera's receiver ids (ShadowMapLayersData).
  void RenderPolygonIds(vtkOpenGLRenderWindow* window);

  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  sl::MeshDrawer Drawer;
  // The last targets rendered, reused by the next frame (or sub-light) when the map size fits; one pair per view for
  // views that partition the pixels (cascades).
  std::vector<vtkSmartPointer<vtkTextureObject>> LinearTargets;
  std::vector<vtkSmartPointer<vtkTextureObject>> DepthTargets;
  // The depth buffer of the two peeled layers' passes (depth_layer = midpoint or dual), and the pass combining them.
  vtkSmartPointer<vtkTextureObject> PeelDepth;
  sl::FullScreenQuad CombineQuad;
};
