// What a technique's CPU twin did for one pixel (`shadowlab probe`, issue 15): every intermediate it computed,
// with its unit and the paper's equation or algorithm line, and the light-space and light-plane geometry it
// touched (texels read, hierarchy nodes visited, kernels, back-projected polygons, light samples).
//
// The twins take an optional `ProbeRecorder*` (nullptr in the tests' whole-image sweeps, so recording costs a
// branch there); `shadowlab probe` passes one for the pixel it replays. The record is written as probe.json
// (probe/ProbeWriter.h), probe.vtm and probe.png. Nothing here knows VTK or a technique.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace sl
{

// One computed quantity of the replay, e.g. {group "blocker search", name "average_blocker_depth", value
// {2.31}, unit "linear depth", source "Eq. 1, PCSS (Fernando 2005)"}.
struct ProbeQuantity
{
  std::string group;          // the step it belongs to, in the order the twin took them: "receiver", "blocker search"
  std::string name;           // snake_case
  std::vector<double> value;  // 1 (scalar), 2 or 3 components (a texel position, a world point)
  std::string unit;           // "texels", "world units", "linear depth", "window depth", "count", "" for fractions
  std::string source;         // the paper's equation or algorithm line ("Eq. 4, VSSM (Yang et al. 2010)"), or
                              // "ShadowLab" for a project definition (docs/tools.md)
  std::string text;           // a categorical value's label ("penumbra"); empty for numbers
};

// A shadow-map texel the twin read.
struct ProbeTexel
{
  glm::ivec2 texel{ 0 };
  std::string role;            // "blocker search", "filter tap", "micropatch", ...
  double storedDepth = 0.0;    // linear depth in the map (window depth where unit says so)
  double comparedDepth = std::numeric_limits<double>::quiet_NaN(); // the receiver's comparison depth; NaN: read only
  bool occluding = false;      // the comparison found the texel in front of the receiver
  double weight = 1.0;         // its contribution's weight (a filter tap's), 1 when it has none
};

// A node of a hierarchy the twin visited: HSM / MSSM / Y shadow map nodes, a quadtree cell, a microrect level.
struct ProbeNode
{
  std::string structure;       // "hsm", "mssm", "quadtree", "microrect"
  int level = 0;
  glm::ivec2 lo{ 0 };          // the shadow-map texels it covers, inclusive
  glm::ivec2 hi{ 0 };
  double minDepth = 0.0;       // the depth range the node holds (linear), NaN where it holds none
  double maxDepth = 0.0;
  std::string decision;        // "lit", "umbra", "descend", "leaf", "pruned", ...
};

// A rectangle in shadow-map texel coordinates (continuous: texel i spans [i, i + 1]): kernels and sub-kernels.
struct ProbeKernel
{
  std::string role;            // "blocker search", "penumbra", "sub-kernel", "packet"
  glm::dvec2 lo{ 0.0 };
  glm::dvec2 hi{ 0.0 };
  std::string label;           // a class ("non-planar", "lit"), empty if none
  std::string source;
};

// A polygon on the light plane, in light coordinates: the light view's x and y (LightView::viewFromWorld, the
// frame the back-projection code works in), world units from the light's centre. A back-projected micropatch or micro-occluder, a contour edge's triangle fan, ...
struct ProbeLightPolygon
{
  std::string role;
  std::vector<glm::dvec2> points;
  double signedArea = 0.0;     // what it contributes over the light (after clipping), world units^2
};

// A contour edge in shadow-map texel coordinates and its back-projection onto the light plane (light
// coordinates), with the signed area its fan covers on the light.
struct ProbeContourEdge
{
  glm::dvec2 a{ 0.0 };
  glm::dvec2 b{ 0.0 };
  glm::dvec2 lightA{ 0.0 };
  glm::dvec2 lightB{ 0.0 };
  double signedArea = 0.0;
};

// A polygon in shadow-map texel coordinates: the probed pixel's footprint (its square on the receiver's tangent
// plane, each corner projected into the map through the light matrix, a warp included).
struct ProbeMapPolygon
{
  std::string role;            // "pixel footprint"
  std::vector<glm::dvec2> points;
  std::string source;
};

// A light sample (light coordinates) and what the twin decided for it.
struct ProbeLightSample
{
  glm::dvec2 position{ 0.0 };
  bool blocked = false;
  int depthComplexity = -1;    // occluders crossed, where the technique counts them; -1 otherwise
};

struct ProbeRecord
{
  std::vector<ProbeQuantity> quantities;
  std::vector<ProbeTexel> texels;
  std::vector<ProbeNode> nodes;
  std::vector<ProbeKernel> kernels;
  std::vector<ProbeLightPolygon> lightPolygons;
  std::vector<ProbeContourEdge> contourEdges;
  std::vector<ProbeLightSample> lightSamples;
  std::vector<ProbeMapPolygon> mapPolygons;
  // Items over ProbeRecorder's caps are counted, not kept (a 500-texel kernel reads 250 000 texels).
  std::size_t droppedTexels = 0;
  std::size_t droppedNodes = 0;
  std::size_t droppedPolygons = 0;
  std::size_t droppedEdges = 0;

  // The first quantity named `name` (in any group), or nullptr.
  const ProbeQuantity* find(const std::string& name) const;
};

// Collects a ProbeRecord. Twins call it through a pointer that is null when nobody probes, so every call site
// reads `if (recorder) recorder->...`.
class ProbeRecorder
{
public:
  static constexpr std::size_t kMaxTexels = 20000;
  static constexpr std::size_t kMaxNodes = 20000;
  static constexpr std::size_t kMaxPolygons = 5000;
  static constexpr std::size_t kMaxEdges = 5000;

  // Quantities of the current group (set by beginGroup, "" until then).
  void beginGroup(std::string group) { group_ = std::move(group); }
  void quantity(const std::string& name, double value, const std::string& unit, const std::string& source);
  void quantity(const std::string& name, const glm::dvec2& value, const std::string& unit, const std::string& source);
  void quantity(const std::string& name, const glm::dvec3& value, const std::string& unit, const std::string& source);
  void category(const std::string& name, const std::string& label, const std::string& source);
  // A categorical value a buffer publishes as a code (e.g. `classification`): the code as the value (compared with
  // the buffer), the label as text.
  void category(const std::string& name, int code, const std::string& label, const std::string& source);

  void texel(ProbeTexel texel);
  void node(ProbeNode node);
  void kernel(ProbeKernel kernel);
  void lightPolygon(ProbeLightPolygon polygon);
  void contourEdge(const ProbeContourEdge& edge);
  void lightSample(const ProbeLightSample& sample);
  void mapPolygon(ProbeMapPolygon polygon);

  const ProbeRecord& record() const { return record_; }
  ProbeRecord& record() { return record_; }

private:
  void add(const std::string& name, std::vector<double> value, const std::string& unit, const std::string& source);

  std::string group_;
  ProbeRecord record_;
};

} // namespace sl
