#include "passes/vtkSLMultiViewPass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "passes/FrameResources.h"
#include "lightspace/LightSamples.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkTextureObject.h>

#include <map>
#include <string>

vtkStandardNewMacro(vtkSLMultiViewPass);

vtkSLMultiViewPass::vtkSLMultiViewPass() = default;
vtkSLMultiViewPass::~vtkSLMultiViewPass() = default;

void vtkSLMultiViewPass::SetStages(std::vector<vtkSLStagePass*> inner, vtkSLSubLightAccumulatePass* accumulate)
{
  this->Inner.assign(inner.begin(), inner.end());
  this->Accumulate = accumulate;
}

void vtkSLMultiViewPass::SetPartitionStages(std::vector<vtkSLStagePass*> inner, vtkSLPartitionAccumulatePass* accumulate)
{
  this->Inner.assign(inner.begin(), inner.end());
  this->PartitionAccumulate = accumulate;
}

void vtkSLMultiViewPass::RenderPartition(const vtkRenderState* state)
{
  sl::FrameResources& frame = *this->Frame;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  std::map<std::string, vtkSmartPointer<vtkTextureObject>> combined;
  // The focus fits every view at view 0: the count is known after it.
  for (int view = 0; view == 0 || (frame.partitions && view < frame.partitions->viewCount()); ++view)
  {
    frame.viewIndex = view;
    for (vtkSLStagePass* stage : this->Inner)
    {
      stage->Render(state);
    }
    if (!frame.partitions)
    {
      // The focus found one map enough (a light that only may need partitions): its targets are the frame's.
      return;
    }
    if (view == 0)
    {
      for (const std::string& output : frame.technique->outputNames())
      {
        combined[output] = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
      }
    }
    this->PartitionAccumulate->SetView(view, &combined);
    this->PartitionAccumulate->Render(state);
  }
  frame.viewIndex = 0;
  frame.techniqueTargets = combined;
}

namespace
{

// Puts the frame's light back however the sub-light loop ends.
struct RestoreLight
{
  sl::FrameResources& frame;
  const sl::Light* light;
  ~RestoreLight() { frame.light = light; }
};

} // namespace

void vtkSLMultiViewPass::Render(const vtkRenderState* state)
{
  SL_CHECK_MSG(this->Frame, "the multi-view pass has no frame resources");
  sl::FrameResources& frame = *this->Frame;
  this->NumberOfRenderedProps = 0;
  SL_CHECK(frame.technique != nullptr);
  if (this->PartitionAccumulate)
  {
    this->RenderPartition(state);
    return;
  }
  const int perSide = frame.technique->subLightsPerSide(frame.parameters);
  frame.subLightVisibility.clear();
  if (perSide == 1)
  {
    for (vtkSLStagePass* stage : this->Inner)
    {
      stage->Render(state);
    }
    frame.subLightVisibility.push_back(frame.techniqueTargets.at("visibility"));
    return;
  }
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  const std::vector<sl::Light> subLights = sl::splitIntoSubLights(*frame.light, perSide);
  std::map<std::string, vtkSmartPointer<vtkTextureObject>> combined;
  for (const std::string& output : frame.technique->outputNames())
  {
    combined[output] = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
  }
  {
    const RestoreLight restore{ frame, frame.light };
    for (std::size_t k = 0; k < subLights.size(); ++k)
    {
      frame.light = &subLights[k];
      if (k > 0)
      {
        // A fresh visibility target, so that each sub-light's is kept for sublight_visibility.
        frame.techniqueTargets["visibility"] = sl::makeFloatTarget(window, frame.width(), frame.height(), 1);
      }
      for (vtkSLStagePass* stage : this->Inner)
      {
        stage->Render(state);
      }
      frame.subLightVisibility.push_back(frame.techniqueTargets.at("visibility"));
      this->Accumulate->SetSubLight(static_cast<int>(k), static_cast<int>(subLights.size()), &combined);
      this->Accumulate->Render(state);
    }
  }
  frame.techniqueTargets = combined;
}

void vtkSLMultiViewPass::ReleaseGraphicsResources(vtkWindow* window)
{
  // The stages are owned and released by the pipeline (ShadowRenderer); nothing of its own.
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSLMultiViewPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InnerStages: " << this->Inner.size() << "\n";
}
