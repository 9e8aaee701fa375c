#include "passes/vtkSLStagePass.h"

#include "core/Error.h"

vtkSLStagePass::vtkSLStagePass() = default;
vtkSLStagePass::~vtkSLStagePass() = default;

void vtkSLStagePass::Render(const vtkRenderState* state)
{
  SL_CHECK_MSG(this->Frame, "pass ", this->GetStageName(), " has no frame resources");
  this->NumberOfRenderedProps = 0;
  sl::checkGlErrors(std::string("before stage ") + this->GetStageName());
  this->Timer.start();
  this->Execute(state);
  this->Timer.stop();
  sl::checkGlErrors(std::string("stage ") + this->GetStageName());
}

void vtkSLStagePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
  os << indent << "WallMilliseconds: " << this->GetWallMilliseconds() << "\n";
}
