// Draws the soft textured shadow volumes of a frame's perforated casters (StsvGeometry.h) for an STSV pass: built on
// the CPU in double, each drawn as the screen polygon of its closed mesh (convexScreenPolygon; the whole viewport for a
// truncated one) with its record of planes and Eq. 1-5 matrices (read by shaders/stsv/StsvSamples.glsl), one draw
// per perforated object with its alpha texture bound. Techniques `penumbra-wedge` (the light-sample mask) and `dcs`
// (the sample counters) use it.
#pragma once

#include "core/Parameters.h"
#include "frame/FrameResult.h"
#include "objectspace/WedgeDrawer.h"
#include "objectspace/StsvGeometry.h"

#include <vtkSmartPointer.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

class vtkPolyData;
class vtkShaderProgram;

namespace sl
{

struct FrameResources;

// The fragment shader that tests a pixel's light samples against the STSVs (Forest et al. 2009 §2.3): dcs and
// penumbra-wedge draw their STSVs with it.
inline constexpr const char* kStsvSamplesShaderPath = "stsv/StsvSamples.glsl";

// The parameter stsv_opposite_side_check of the techniques with STSVs, and the occlusion test it picks.
ParameterSpec stsvOppositeSideCheckParameter();
StsvOcclusionTest stsvOcclusionTestOf(const ParameterValues& values);

// One STSV's record in the wedge pass's storage buffer (WedgeDrawer::addPolygon), in vec4s, declared once: the
// C++ writer (StsvDrawer::prepare) indexes it with these offsets, and shaders/stsv/StsvSamples.glsl reads it through
// the names stsvRecordShaderConstants() generates into the preamble (STSV_RECORD_VEC4 and STSV_RECORD_<FIELD>).
struct StsvRecord
{
  static constexpr int kPlanes = 0; // the three outer planes, then the front cap plane: (normal, offset), inside +
  static constexpr int kPlaneCount = 4;
  static constexpr int kV0 = kPlanes + kPlaneCount; // (the triangle's v0, the light side of its plane)
  static constexpr int kNormal = kV0 + 1;           // (unit normal n, on-plane distance)
  static constexpr int kTriangleFromWorld = kNormal + 1; // M's three columns (Eq. 2), (column, 0)
  static constexpr int kTextureRow0 = kTriangleFromWorld + 3; // S's first row (Eq. 4), (row, 0)
  static constexpr int kTextureRow1 = kTextureRow0 + 1;        // S's second row
  static constexpr int kVec4Count = kTextureRow1 + 1;          // the stride
};
std::vector<ShaderConstant> stsvRecordShaderConstants();

// What the shaders of a wedge pass share with this area's C++ (shaders/dcs/DcsWedgeCommon.glsl and the shaders
// that include it): the outline's corner bound and both records' layouts.
std::vector<ShaderConstant> wedgePassShaderConstants();

class StsvDrawer
{
public:
  // The STSVs of the frame's perforated casters under its light.
  void prepare(const FrameResources& frame);
  // Binds each perforated object's alpha texture (common/AlphaMask.glsl's uniforms) and draws its STSVs with
  // `program` (bound; the caller sets the target, state and the rest of the uniforms).
  // (Fragments are counted with an occlusion query around the draws.)
  void draw(vtkShaderProgram* program, const FrameResources& frame);
  void releaseGraphicsResources();
  // perforated_triangles, stsvs, stsvs_truncated, stsv_build_ms (CPU), stsv_fragments.
  void addStatistics(std::map<std::string, double>& statistics) const;

  std::size_t perforatedTriangles() const { return perforated_.size(); }
  std::size_t volumes() const { return volumes_; }
  std::size_t truncatedVolumes() const { return truncated_; }
  double buildMilliseconds() const { return buildMilliseconds_; }
  // Each STSV's closed mesh (Fig. 6's strip) with cell data stsv_id, caster_id, light_side, truncated: stsv.vtp.
  vtkSmartPointer<vtkPolyData> polyData() const;
  // Appends stsv.vtp to a pass's object-space exports when the frame had STSVs.
  void addExport(std::vector<NamedPolyData>& exports) const;

private:
  struct Range
  {
    std::size_t object = 0;
    std::size_t firstVertex = 0;
    std::size_t vertexCount = 0;
  };
  std::vector<StsvTriangle> perforated_;
  std::vector<std::vector<Stsv>> stsvs_; // per perforated triangle
  std::vector<Range> ranges_;
  std::size_t volumes_ = 0;
  std::size_t truncated_ = 0;
  double buildMilliseconds_ = 0.0;
  WedgeDrawer drawer_;
  unsigned int fragmentQuery_ = 0;
};

} // namespace sl
