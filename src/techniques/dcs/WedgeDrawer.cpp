#include "techniques/dcs/WedgeDrawer.h"

#include "core/Error.h"
#include "gl/ComputeProgram.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"

#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

#include <cstring>
#include <string>

namespace sl
{

WedgeDrawer::WedgeDrawer() = default;
WedgeDrawer::~WedgeDrawer() = default;

std::size_t WedgeDrawer::prepare(const std::vector<DcsWedgeEdge>& wedges, const FrameResources& frame)
{
  vertices_.clear();
  words_.clear();
  const bool perspective = frame.scene->camera.projection == Projection::Perspective;
  const std::vector<glm::dvec3> outline = lightOutline(*frame.light);
  const Bounds bounds = frame.scene->bounds();
  std::size_t drawn = 0;
  for (const DcsWedgeEdge& wedge : wedges)
  {
    const std::vector<glm::dvec2> polygon = wedgeScreenPolygon(wedge, *frame.light, outline, frame.camera, perspective, bounds);
    if (polygon.empty())
    {
      continue;
    }
    const float index = static_cast<float>(drawn++);
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    {
      for (const glm::dvec2& corner : { polygon[0], polygon[k], polygon[k + 1] })
      {
        vertices_.insert(vertices_.end(), { static_cast<float>(corner.x), static_cast<float>(corner.y), index });
      }
    }
    const auto pushVec4 = [&](const glm::dvec3& xyz, float w) {
      for (const float value : { static_cast<float>(xyz.x), static_cast<float>(xyz.y), static_cast<float>(xyz.z), w })
      {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &value, sizeof bits);
        words_.push_back(bits);
      }
    };
    pushVec4(wedge.v0, static_cast<float>(wedge.oppositeCount));
    pushVec4(wedge.v1, 0.0f);
    pushVec4(wedge.opposite[0], 0.0f);
    pushVec4(wedge.oppositeCount > 1 ? wedge.opposite[1] : wedge.opposite[0], 0.0f);
  }
  return drawn;
}

void WedgeDrawer::draw(vtkShaderProgram* program, const Light& light)
{
  if (vertices_.empty())
  {
    return;
  }
  if (!data_ || dataWords_ != words_.size())
  {
    data_ = std::make_unique<StorageBuffer>(words_.size());
    dataWords_ = words_.size();
  }
  data_->upload(words_);
  if (!vertexBuffer_)
  {
    vertexBuffer_ = vtkSmartPointer<vtkOpenGLBufferObject>::New();
    vertexBuffer_->SetType(vtkOpenGLBufferObject::ArrayBuffer);
  }
  if (!vertexBuffer_->Upload(vertices_, vtkOpenGLBufferObject::ArrayBuffer))
  {
    throw GraphicsError("cannot upload " + std::to_string(vertices_.size() / 3) + " wedge vertices: " + vertexBuffer_->GetError());
  }
  setWedgeLightUniforms(program, light);
  data_->bind(0);
  if (vertexArray_)
  {
    vertexArray_->ReleaseGraphicsResources();
  }
  vertexArray_ = vtkSmartPointer<vtkOpenGLVertexArrayObject>::New();
  vertexArray_->Bind();
  const int stride = 3 * sizeof(float);
  vertexArray_->AddAttributeArray(program, vertexBuffer_, "wedgeNdcIn", 0, stride, VTK_FLOAT, 2, false);
  vertexArray_->AddAttributeArray(program, vertexBuffer_, "wedgeIndexIn", 2 * sizeof(float), stride, VTK_FLOAT, 1, false);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size() / 3));
  vertexArray_->Release();
}

void WedgeDrawer::releaseGraphicsResources()
{
  if (vertexArray_)
  {
    vertexArray_->ReleaseGraphicsResources();
    vertexArray_ = nullptr;
  }
  if (vertexBuffer_)
  {
    vertexBuffer_->ReleaseGraphicsResources();
    vertexBuffer_ = nullptr;
  }
  data_.reset();
  dataWords_ = 0;
}

void setWedgeLightUniforms(vtkShaderProgram* program, const Light& light)
{
  setVector(program, "dcsLightCenter", light.center);
  setVector(program, "dcsLightRight", light.right());
  setVector(program, "dcsLightUp", light.up);
  setVector(program, "dcsLightNormal", light.normal);
  const std::vector<glm::dvec3> outline = lightOutline(light);
  std::vector<float> corners;
  for (const glm::dvec3& corner : outline)
  {
    corners.insert(corners.end(), { static_cast<float>(corner.x), static_cast<float>(corner.y), static_cast<float>(corner.z) });
  }
  program->SetUniform3fv("dcsOutline", static_cast<int>(outline.size()), reinterpret_cast<const float(*)[3]>(corners.data()));
  program->SetUniformi("dcsOutlineCorners", static_cast<int>(outline.size()));
}

} // namespace sl
