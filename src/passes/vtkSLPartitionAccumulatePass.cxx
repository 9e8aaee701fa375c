#include "passes/vtkSLPartitionAccumulatePass.h"

#include "core/Error.h"
#include "gl/ShaderLibrary.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <set>

vtkStandardNewMacro(vtkSLPartitionAccumulatePass);

vtkSLPartitionAccumulatePass::vtkSLPartitionAccumulatePass() = default;
vtkSLPartitionAccumulatePass::~vtkSLPartitionAccumulatePass() = default;

void vtkSLPartitionAccumulatePass::SetView(
  int index, const std::map<std::string, vtkSmartPointer<vtkTextureObject>>* combined)
{
  this->ViewIndex = index;
  this->Combined = combined;
}

void vtkSLPartitionAccumulatePass::Execute(const vtkRenderState*)
{
  const sl::FrameResources& frame = *this->Frame;
  SL_CHECK_MSG(this->Combined && frame.viewSelection, "partition_accumulate runs inside the multi-view pass");
  if (!this->Program)
  {
    this->Program = std::make_unique<sl::ComputeProgram>(
      sl::assembleShader("multiview/PartitionAccumulate.glsl", {}), "partition accumulation");
  }
  this->Program->use();
  this->Program->setInt("imageWidth", frame.width());
  this->Program->setInt("imageHeight", frame.height());
  this->Program->setInt("viewIndex", this->ViewIndex);
  std::set<std::string> categorical;
  for (const sl::BufferSpec& buffer : frame.technique->buffers)
  {
    if (buffer.kind == sl::BufferKind::Categorical)
    {
      categorical.insert(buffer.name);
    }
  }
  glBindImageTexture(2, frame.viewSelection->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  for (const std::string& output : frame.technique->outputNames())
  {
    this->Program->setInt("categorical", categorical.count(output) ? 1 : 0);
    glBindImageTexture(0, frame.techniqueTargets.at(output)->GetHandle(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(1, this->Combined->at(output)->GetHandle(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    this->Program->dispatch({ (frame.width() + 7) / 8, (frame.height() + 7) / 8 });
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
  glBindImageTexture(2, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
}

void vtkSLPartitionAccumulatePass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Program.reset();
}

void vtkSLPartitionAccumulatePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "View: " << this->ViewIndex << "\n";
}
