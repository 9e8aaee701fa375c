#include "structures/lightsamples/vtkSLLightSamplePass.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "passes/FrameResources.h"

#include <vtkObjectFactory.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>

#include <vector>

vtkStandardNewMacro(vtkSLLightSamplePass);

vtkSLLightSamplePass::vtkSLLightSamplePass() = default;
vtkSLLightSamplePass::~vtkSLLightSamplePass() = default;

namespace
{

bool sameSettings(const sl::LightSampleSetSettings& a, const sl::LightSampleSetSettings& b)
{
  return a.pattern == b.pattern && a.interleaved == b.interleaved && a.count == b.count && a.seed == b.seed;
}

} // namespace

void vtkSLLightSamplePass::Execute(const vtkRenderState* state)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(state->GetRenderer()->GetRenderWindow());
  sl::FrameResources& frame = *this->Frame;
  const sl::LightSampleSetSettings settings = sl::lightSampleSetSettings(frame.parameters);
  // The set is the same every frame until a parameter changes: constructing a Poisson set costs up to a few
  // milliseconds, the upload a texture allocation.
  if (!this->Samples || !sameSettings(this->Samples->settings(), settings) || !this->BaseTexture ||
    this->BaseTexture->GetContext() != window)
  {
    this->Samples = std::make_shared<const sl::LightSampleSet>(settings);
    const std::vector<glm::dvec2>& points = this->Samples->basePoints();
    std::vector<float> texels;
    texels.reserve(2 * points.size());
    for (const glm::dvec2& point : points)
    {
      // Multiples of 2^-16 in [0, 1): exact in float.
      texels.push_back(static_cast<float>(point.x));
      texels.push_back(static_cast<float>(point.y));
    }
    const int count = static_cast<int>(points.size());
    this->BaseTexture = sl::makeFloatTarget(window, count, 1, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(this->BaseTexture->GetHandle(), 0, 0, 0, count, 1, GL_RG, GL_FLOAT, texels.data());
    sl::checkGlErrors("uploading the light samples");
    ++this->UploadCount;
  }
  auto data = std::make_shared<sl::LightSampleSetData>();
  data->samples = this->Samples;
  data->baseTexture = this->BaseTexture;
  frame.lightSpaceData[sl::lightSampleSetStructure().name] = data;
}

void vtkSLLightSamplePass::ReleaseGraphicsResources(vtkWindow*)
{
  this->Samples.reset();
  this->BaseTexture = nullptr;
}

void vtkSLLightSamplePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UploadCount: " << this->UploadCount << "\n";
}
