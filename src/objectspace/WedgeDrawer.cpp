#include "objectspace/WedgeDrawer.h"

#include "core/Error.h"
#include "gl/ComputeProgram.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"

#include <vtkOpenGLBufferObject.h>
#include <vtkOpenGLVertexArrayObject.h>
#include <vtkShaderProgram.h>
#include <vtk_glew.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <tuple>

namespace sl
{

static_assert(WedgeRecord::kOppositeCount == std::tuple_size<decltype(DcsWedgeEdge::opposite)>::value,
  "a wedge record holds the third corner of each of the edge's triangles");

WedgeDrawer::WedgeDrawer() = default;
WedgeDrawer::~WedgeDrawer() = default;

void WedgeDrawer::clear()
{
  uploaded_ = false;
  vertices_.clear();
  words_.clear();
  polygons_ = 0;
}

void WedgeDrawer::addPolygon(const std::vector<glm::dvec2>& polygon, const Vec4Record& record)
{
  uploaded_ = false;
  const float index = static_cast<float>(polygons_++); // exact: fewer than 2^24 polygons
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
  {
    for (const glm::dvec2& corner : { polygon[0], polygon[k], polygon[k + 1] })
    {
      vertices_.insert(vertices_.end(), { static_cast<float>(corner.x), static_cast<float>(corner.y), index });
    }
  }
  for (const glm::vec4& vec4 : record.vec4s)
  {
    for (int component = 0; component < vec4.length(); ++component)
    {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &vec4[component], sizeof bits);
      words_.push_back(bits);
    }
  }
}

std::vector<ShaderConstant> wedgeRecordShaderConstants()
{
  return {
    { "WEDGE_RECORD_VEC4", WedgeRecord::kVec4Count, "vec4s per wedge record (WedgeDrawer.h WedgeRecord)" },
    { "WEDGE_RECORD_V0", WedgeRecord::kV0, "a wedge record's (v0, number of triangles)" },
    { "WEDGE_RECORD_V1", WedgeRecord::kV1, "a wedge record's (v1, 0)" },
    { "WEDGE_RECORD_OPPOSITE", WedgeRecord::kOpposite, "a wedge record's first (w_k, 0), the third corner of triangle k" },
  };
}

std::size_t WedgeDrawer::prepare(const std::vector<DcsWedgeEdge>& wedges, const FrameResources& frame)
{
  clear();
  const bool perspective = frame.scene->camera.projection == Projection::Perspective;
  const std::vector<glm::dvec3> outline = lightOutline(*frame.light);
  const Bounds bounds = frame.scene->bounds();
  for (const DcsWedgeEdge& wedge : wedges)
  {
    const std::vector<glm::dvec2> polygon = wedgeScreenPolygon(wedge, *frame.light, outline, frame.camera, perspective, bounds);
    if (polygon.empty())
    {
      continue;
    }
    Vec4Record record(WedgeRecord::kVec4Count);
    record.set(WedgeRecord::kV0, wedge.v0, wedge.oppositeCount);
    record.set(WedgeRecord::kV1, wedge.v1, 0.0);
    for (int k = 0; k < WedgeRecord::kOppositeCount; ++k)
    {
      record.set(WedgeRecord::kOpposite + k, k < wedge.oppositeCount ? wedge.opposite[k] : wedge.opposite[0], 0.0);
    }
    addPolygon(polygon, record);
  }
  return polygons_;
}

void WedgeDrawer::draw(vtkShaderProgram* program, const Light& light)
{
  draw(program, light, 0, vertexCount());
}

void WedgeDrawer::drawCounted(vtkShaderProgram* program, const Light& light)
{
  if (fragmentQuery_ == 0)
  {
    glGenQueries(1, &fragmentQuery_);
  }
  glBeginQuery(GL_SAMPLES_PASSED, fragmentQuery_);
  draw(program, light);
  glEndQuery(GL_SAMPLES_PASSED);
}

void WedgeDrawer::drawCounted(vtkShaderProgram* program, const Light& light, std::size_t chunks,
  const std::function<void(std::size_t)>& afterChunk)
{
  if (fragmentQuery_ == 0)
  {
    glGenQueries(1, &fragmentQuery_);
  }
  glBeginQuery(GL_SAMPLES_PASSED, fragmentQuery_);
  const std::size_t triangles = vertexCount() / 3;
  chunks = std::max<std::size_t>(1, std::min(chunks, triangles));
  for (std::size_t c = 0; c < chunks; ++c)
  {
    const std::size_t first = triangles * c / chunks;
    const std::size_t last = triangles * (c + 1) / chunks;
    draw(program, light, 3 * first, 3 * (last - first));
    if (afterChunk)
    {
      afterChunk(c + 1);
    }
  }
  glEndQuery(GL_SAMPLES_PASSED);
}

std::size_t WedgeDrawer::fragments() const
{
  GLuint fragments = 0;
  if (fragmentQuery_ != 0)
  {
    glGetQueryObjectuiv(fragmentQuery_, GL_QUERY_RESULT, &fragments);
  }
  return fragments;
}

void WedgeDrawer::draw(vtkShaderProgram* program, const Light& light, std::size_t firstVertex, std::size_t count)
{
  if (vertices_.empty() || count == 0)
  {
    return;
  }
  // Uploaded once per prepare (an STSV pass draws one range per perforated object).
  if (!uploaded_)
  {
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
      throw GraphicsError(
        "cannot upload " + std::to_string(vertices_.size() / 3) + " wedge vertices: " + vertexBuffer_->GetError());
    }
    uploaded_ = true;
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
  glDrawArrays(GL_TRIANGLES, static_cast<GLint>(firstVertex), static_cast<GLsizei>(count));
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
  uploaded_ = false;
  if (fragmentQuery_ != 0)
  {
    glDeleteQueries(1, &fragmentQuery_);
    fragmentQuery_ = 0;
  }
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
