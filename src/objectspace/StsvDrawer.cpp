#include "objectspace/StsvDrawer.h"

#include "core/Error.h"
#include "gl/GlResources.h"
#include "passes/FrameResources.h"
#include "passes/PassUtilities.h"
#include "objectspace/DcsGeometry.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <tuple>

namespace sl
{

ParameterSpec stsvOppositeSideCheckParameter()
{
  return { "stsv_opposite_side_check", 1, 0, 1, "",
    "STSVs: also require a sample and the point to lie on opposite sides of the perforated triangle's plane (h.z > 1), the test the paper's Eq. 1 lacks (reading notes C5; inside the volumes it changes nothing, src/objectspace/Stsv.md); off = the paper's test alone",
    { "off", "on" }, true };
}

StsvOcclusionTest stsvOcclusionTestOf(const ParameterValues& values)
{
  return values.choice("stsv_opposite_side_check") == "on" ? StsvOcclusionTest::PaperAndOppositeSides
                                                            : StsvOcclusionTest::Paper;
}

static_assert(StsvRecord::kPlaneCount == std::tuple_size<decltype(Stsv::outerPlanes)>::value + 1,
  "an STSV record holds the outer planes and the front cap plane");

std::vector<ShaderConstant> stsvRecordShaderConstants()
{
  return {
    { "STSV_RECORD_VEC4", StsvRecord::kVec4Count, "vec4s per STSV record (StsvDrawer.h StsvRecord)" },
    { "STSV_RECORD_PLANES", StsvRecord::kPlanes, "an STSV record's outer planes and front cap plane" },
    { "STSV_RECORD_PLANE_COUNT", StsvRecord::kPlaneCount, "planes in an STSV record" },
    { "STSV_RECORD_V0", StsvRecord::kV0, "an STSV record's (v0, light side)" },
    { "STSV_RECORD_NORMAL", StsvRecord::kNormal, "an STSV record's (normal, on-plane distance)" },
    { "STSV_RECORD_TRIANGLE_FROM_WORLD", StsvRecord::kTriangleFromWorld, "an STSV record's first column of M" },
    { "STSV_RECORD_TEXTURE_ROW0", StsvRecord::kTextureRow0, "an STSV record's first row of S" },
    { "STSV_RECORD_TEXTURE_ROW1", StsvRecord::kTextureRow1, "an STSV record's second row of S" },
  };
}

std::vector<ShaderConstant> wedgePassShaderConstants()
{
  std::vector<ShaderConstant> constants = {
    { "DCS_MAX_OUTLINE_CORNERS", kDcsMaxOutlineCorners, "corners of a light's outline (DcsGeometry.h lightOutline)" },
  };
  for (const std::vector<ShaderConstant>& record : { wedgeRecordShaderConstants(), stsvRecordShaderConstants() })
  {
    constants.insert(constants.end(), record.begin(), record.end());
  }
  return constants;
}

void StsvDrawer::prepare(const FrameResources& frame)
{
  const auto buildStart = std::chrono::steady_clock::now();
  perforated_ = sl::perforatedTriangles(*frame.scene);
  stsvs_.clear();
  ranges_.clear();
  volumes_ = 0;
  truncated_ = 0;
  drawer_.clear();
  const bool perspective = frame.scene->camera.projection == Projection::Perspective;
  const Bounds bounds = frame.scene->bounds();
  const std::vector<glm::dvec2> viewport = { { -1.0, -1.0 }, { 1.0, -1.0 }, { 1.0, 1.0 }, { -1.0, 1.0 } };
  for (const StsvTriangle& triangle : perforated_)
  {
    stsvs_.push_back(buildStsvs(triangle, *frame.light, bounds));
    if (ranges_.empty() || ranges_.back().object != triangle.objectIndex)
    {
      ranges_.push_back({ triangle.objectIndex, drawer_.vertexCount(), 0 });
    }
    const double onPlaneDistance = stsvOnPlaneDistance(triangle);
    for (const Stsv& stsv : stsvs_.back())
    {
      ++volumes_;
      truncated_ += stsv.closedVolumeTruncated;
      std::vector<glm::dvec4> clip;
      for (std::size_t k = 0; k < 3; ++k)
      {
        clip.push_back(frame.camera.clipFromWorld * glm::dvec4(stsv.frontCap[k], 1.0));
        clip.push_back(frame.camera.clipFromWorld * glm::dvec4(stsv.backCap[k], 1.0));
      }
      const std::vector<glm::dvec2> polygon =
        stsv.closedVolumeTruncated ? viewport : convexScreenPolygon(clip, frame.camera, perspective);
      if (polygon.empty())
      {
        continue;
      }
      // The record of shaders/stsv/StsvSamples.glsl.
      Vec4Record record(StsvRecord::kVec4Count);
      for (std::size_t k = 0; k < stsv.outerPlanes.size(); ++k)
      {
        record.set(StsvRecord::kPlanes + static_cast<int>(k), stsv.outerPlanes[k].normal, stsv.outerPlanes[k].offset);
      }
      record.set(StsvRecord::kPlanes + static_cast<int>(stsv.outerPlanes.size()), stsv.frontCapPlane.normal,
        stsv.frontCapPlane.offset);
      record.set(StsvRecord::kV0, triangle.vertices[0], stsv.lightSide);
      record.set(StsvRecord::kNormal, triangle.normal, onPlaneDistance);
      for (int column = 0; column < 3; ++column)
      {
        record.set(StsvRecord::kTriangleFromWorld + column, triangle.triangleFromWorld[column], 0.0);
      }
      const glm::dmat3& textureFromBarycentric = triangle.textureFromBarycentric;
      const auto textureRow = [&](int row) {
        return glm::dvec3(textureFromBarycentric[0][row], textureFromBarycentric[1][row], textureFromBarycentric[2][row]);
      };
      record.set(StsvRecord::kTextureRow0, textureRow(0), 0.0);
      record.set(StsvRecord::kTextureRow1, textureRow(1), 0.0);
      drawer_.addPolygon(polygon, record);
    }
    ranges_.back().vertexCount = drawer_.vertexCount() - ranges_.back().firstVertex;
  }
  buildMilliseconds_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart).count();
}

void StsvDrawer::draw(vtkShaderProgram* program, const FrameResources& frame)
{
  if (fragmentQuery_ == 0)
  {
    glGenQueries(1, &fragmentQuery_);
  }
  glBeginQuery(GL_SAMPLES_PASSED, fragmentQuery_);
  for (const Range& range : ranges_)
  {
    const SceneObject* object = &frame.scene->objects[range.object];
    const std::vector<GpuMesh>& meshes = frame.gpuScene->meshes();
    const auto mesh = std::find_if(meshes.begin(), meshes.end(), [&](const GpuMesh& m) { return m.object == object; });
    SL_CHECK_MSG(mesh != meshes.end() && mesh->alphaTexture, "a perforated caster without its alpha texture on the GPU");
    program->SetUniformi("hasAlphaTexture", 1);
    vtkTextureObject* alpha = bindTexture(program, "alphaTexture", mesh->alphaTexture);
    drawer_.draw(program, *frame.light, range.firstVertex, range.vertexCount);
    alpha->Deactivate();
  }
  glEndQuery(GL_SAMPLES_PASSED);
}

void StsvDrawer::releaseGraphicsResources()
{
  drawer_.releaseGraphicsResources();
  if (fragmentQuery_ != 0)
  {
    glDeleteQueries(1, &fragmentQuery_);
    fragmentQuery_ = 0;
  }
}

void StsvDrawer::addStatistics(std::map<std::string, double>& statistics) const
{
  statistics["perforated_triangles"] = static_cast<double>(perforated_.size());
  statistics["stsvs"] = static_cast<double>(volumes_);
  statistics["stsvs_truncated"] = static_cast<double>(truncated_);
  statistics["stsv_build_ms"] = buildMilliseconds_;
  GLuint fragments = 0;
  if (fragmentQuery_ != 0)
  {
    glGetQueryObjectuiv(fragmentQuery_, GL_QUERY_RESULT, &fragments);
  }
  statistics["stsv_fragments"] = static_cast<double>(fragments);
}

vtkSmartPointer<vtkPolyData> StsvDrawer::polyData() const
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkIntArray> stsvId;
  stsvId->SetName("stsv_id");
  vtkNew<vtkIntArray> casterId;
  casterId->SetName("caster_id");
  vtkNew<vtkIntArray> lightSide;
  lightSide->SetName("light_side");
  vtkNew<vtkIntArray> truncated;
  truncated->SetName("truncated");
  int id = 0;
  for (std::size_t t = 0; t < perforated_.size(); ++t)
  {
    for (const Stsv& stsv : stsvs_[t])
    {
      const std::array<glm::dvec3, 10> strip = stsvStrip(stsv);
      const vtkIdType first = points->GetNumberOfPoints();
      for (const glm::dvec3& corner : strip)
      {
        points->InsertNextPoint(corner.x, corner.y, corner.z);
      }
      for (vtkIdType k = 0; k + 2 < 10; ++k)
      {
        // GL's strip rule: odd triangles swap their first two vertices, so every one faces outwards.
        const vtkIdType triangle[3] = { first + (k % 2 ? k + 1 : k), first + (k % 2 ? k : k + 1), first + k + 2 };
        triangles->InsertNextCell(3, triangle);
        stsvId->InsertNextValue(id);
        casterId->InsertNextValue(static_cast<int>(perforated_[t].objectIndex));
        lightSide->InsertNextValue(stsv.lightSide);
        truncated->InsertNextValue(stsv.closedVolumeTruncated ? 1 : 0);
      }
      ++id;
    }
  }
  auto volumes = vtkSmartPointer<vtkPolyData>::New();
  volumes->SetPoints(points);
  volumes->SetPolys(triangles);
  volumes->GetCellData()->AddArray(stsvId);
  volumes->GetCellData()->AddArray(casterId);
  volumes->GetCellData()->AddArray(lightSide);
  volumes->GetCellData()->AddArray(truncated);
  return volumes;
}

void StsvDrawer::addExport(std::vector<NamedPolyData>& exports) const
{
  if (volumes_ > 0)
  {
    exports.push_back({ "stsv",
      "each soft textured shadow volume's closed mesh (Fig. 6's strip, 8 triangles); cell data stsv_id, caster_id, "
      "light_side (+1: the light piece on the triangle normal's side), truncated (the mesh may miss part of the box)",
      polyData() });
  }
}

} // namespace sl
