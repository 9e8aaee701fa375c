#include "passes/vtkSLStagePass.h"

#include "core/Error.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLShaderCache.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>

vtkSLStagePass::vtkSLStagePass() = default;
vtkSLStagePass::~vtkSLStagePass() = default;

void vtkSLStagePass::Render(const vtkRenderState* state)
{
  SL_CHECK_MSG(this->Frame, "pass ", this->GetStageName(), " has no frame resources");
  this->NumberOfRenderedProps = 0;
  if (this->Reuse && this->Reuse->restore(*this->Frame))
  {
    ++this->ReusedRuns; // untimed: a reused build costs nothing on the GPU
    // The skipped build would have bound its programs through VTK's shader cache. Without it, a compute program an
    // earlier stage bound outside the cache (the focus's receiver reduction) stays bound while the cache believes
    // its own last program is, and a later draw with that program would skip binding it (GL_INVALID_OPERATION: the
    // temporal pass's moving-camera G-buffer). The cache forgets its program, so the next draw binds one.
    if (auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow()))
    {
      window->GetShaderCache()->ReleaseCurrentShader();
    }
    return;
  }
  sl::checkGlErrors(std::string("before stage ") + this->GetStageName());
  const double gpuBefore = this->Timer.gpuMilliseconds();
  this->Timer.start();
  this->Execute(state);
  this->Timer.stop();
  sl::checkGlErrors(std::string("stage ") + this->GetStageName());
  ++this->ExecutedRuns;
  if (this->Reuse)
  {
    this->Reuse->remember(*this->Frame, this->Timer.gpuMilliseconds() - gpuBefore);
  }
}

void vtkSLStagePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Stage: " << this->GetStageName() << "\n";
  os << indent << "WallMilliseconds: " << this->GetWallMilliseconds() << "\n";
  os << indent << "ExecutedRuns: " << this->ExecutedRuns << ", ReusedRuns: " << this->ReusedRuns << "\n";
}
