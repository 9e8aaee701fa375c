// Draws wedges (DcsGeometry.h) for a wedge pass: each wedge as its screen polygon (wedgeScreenPolygon, built on the
// CPU in double), fan-triangulated, every vertex carrying the wedge's index (shaders/dcs/DcsWedgeVertex.glsl), and
// the wedges' data in a storage buffer at binding 0 with the light's frame and outline as uniforms
// (shaders/dcs/DcsWedgeCommon.glsl). Technique `dcs` draws its potential silhouettes with it, `penumbra-wedge` its
// centre silhouettes. The caller sets the render target and raster state and owns the fragment shader.
#pragma once

#include "scene/Scene.h"
#include "frame/TechniqueDescriptor.h"
#include "objectspace/DcsGeometry.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

class vtkOpenGLBufferObject;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;

namespace sl
{

struct FrameResources;
class StorageBuffer;

// A record of the wedge pass's storage buffer (binding 0, `wedgeData`), in vec4s, declared once: the C++ writer
// (WedgeDrawer::prepare) indexes it with these offsets, and the shaders read it through the names
// wedgeRecordShaderConstants() generates into their preamble (WEDGE_RECORD_VEC4 and WEDGE_RECORD_<FIELD>).
// The vertex shader every wedge pass draws its wedges' screen polygons with (dcs, penumbra-wedge).
inline constexpr const char* kWedgeVertexShaderPath = "dcs/DcsWedgeVertex.glsl";

struct WedgeRecord
{
  static constexpr int kV0 = 0;       // (v0, number of triangles)
  static constexpr int kV1 = 1;       // (v1, 0)
  static constexpr int kOpposite = 2; // (w_k, 0) for the edge's triangles k = 0, 1: their third corners
  static constexpr int kOppositeCount = 2;
  static constexpr int kVec4Count = kOpposite + kOppositeCount; // the stride
};
std::vector<ShaderConstant> wedgeRecordShaderConstants();

// A record being written: `vec4Count` vec4s of floats, field by field.
struct Vec4Record
{
  explicit Vec4Record(int vec4Count) : vec4s(static_cast<std::size_t>(vec4Count), glm::vec4(0.0f)) {}
  // The vec4 at offset `field` (xyz, w), rounded to float.
  void set(int field, const glm::dvec3& xyz, double w)
  {
    vec4s.at(static_cast<std::size_t>(field)) = glm::vec4(glm::vec3(xyz), static_cast<float>(w));
  }
  std::vector<glm::vec4> vec4s;
};

class WedgeDrawer
{
public:
  WedgeDrawer();
  ~WedgeDrawer();
  WedgeDrawer(const WedgeDrawer&) = delete;
  WedgeDrawer& operator=(const WedgeDrawer&) = delete;

  // The screen polygons and data of `wedges` under the frame's light and camera; returns how many have a polygon
  // (a wedge no receiver in view can lie in has none and is not drawn).
  std::size_t prepare(const std::vector<DcsWedgeEdge>& wedges, const FrameResources& frame);
  // Any other convex screen polygons with a record each (STSVs, StsvRecord): clear, then add them in order; the
  // fragment shader reads polygon i's record at index i (wedgeIndex) with the record's generated stride.
  void clear();
  void addPolygon(const std::vector<glm::dvec2>& polygon, const Vec4Record& record);
  std::size_t vertexCount() const { return vertices_.size() / 3; }
  // Uploads what prepare built, binds the data (binding 0), sets the light uniforms and the vertex attributes of
  // `program` (bound), and draws the polygons (or the vertices [firstVertex, firstVertex + count) of them). Nothing
  // to draw: nothing happens.
  void draw(vtkShaderProgram* program, const Light& light);
  void draw(vtkShaderProgram* program, const Light& light, std::size_t firstVertex, std::size_t count);
  // draw(program, light) counting the fragments rasterised with an occlusion query (the wedge passes' shaders never
  // discard, so every fragment passes); fragments() reads the count of the last such draw (0 before any).
  void drawCounted(vtkShaderProgram* program, const Light& light);
  // The same in `chunks` consecutive ranges of whole triangles (the same fragments in the same order), calling
  // afterChunk(k) after the k-th (1-based): where dcs reports progress on a long frame (core/Progress.h).
  void drawCounted(vtkShaderProgram* program, const Light& light, std::size_t chunks,
    const std::function<void(std::size_t)>& afterChunk);
  std::size_t fragments() const;
  void releaseGraphicsResources();

private:
  std::vector<float> vertices_;       // per vertex: NDC x, y and the polygon's index
  std::vector<std::uint32_t> words_;  // the records (WedgeRecord, StsvRecord), their floats' bits
  std::size_t polygons_ = 0;
  bool uploaded_ = false; // vertices_ and words_ are on the GPU
  unsigned int fragmentQuery_ = 0;
  std::unique_ptr<StorageBuffer> data_;
  std::size_t dataWords_ = 0;
  vtkSmartPointer<vtkOpenGLBufferObject> vertexBuffer_;
  vtkSmartPointer<vtkOpenGLVertexArrayObject> vertexArray_;
};

// The light uniforms of shaders/dcs/DcsWedgeCommon.glsl: centre, frame, normal and outline.
void setWedgeLightUniforms(vtkShaderProgram* program, const Light& light);

} // namespace sl
