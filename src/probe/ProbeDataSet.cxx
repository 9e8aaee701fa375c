// probe.vtm (probe/Probe.h): what a probe recorded as VTK data for ParaView, in three blocks of named pieces.
//   world        light, receiver, rays_to_light, rays_to_samples, kernel_frustum   (world space)
//   shadow_map   crop (vtkStructuredGrid, one cell per texel), visited_nodes, kernels, receiver, pixel_footprint
//                (world space: the map's texels placed on the plane through the receiver perpendicular to the
//                light's axis, texel (u, v) at worldFromTexel(view, (u, v), d_receiver), so the crop lies under
//                the receiver and its kernels over the scene; every point keeps its texel coordinates in the
//                point array texel_uv: texel i spans [i, i + 1])
//   light_plane  light_outline, polygons, contour_edges, light_samples            (world space, on the light plane)
// One coordinate system, world units, for every block (issue 31: the shadow_map block in texel units landed far
// from the others in ParaView); each block names it in its field data `coordinates`. Every piece is present,
// possibly empty, so the block layout is the same for every technique.
#include "probe/Probe.h"

#include "probe/ProbeGeometry.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkStructuredGrid.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// A vtkPolyData built cell by cell, with cell arrays filled alongside.
class PolyBuilder
{
public:
  PolyBuilder()
  {
    points_->SetDataTypeToDouble(); // world positions exactly as recorded
    data_->SetPoints(points_);
    data_->SetVerts(verts_);
    data_->SetLines(lines_);
    data_->SetPolys(polys_);
  }

  vtkIdType point(const glm::dvec3& p) { return points_->InsertNextPoint(p.x, p.y, p.z); }
  void vertex(vtkIdType id) { verts_->InsertNextCell(1, &id); }
  void line(vtkIdType a, vtkIdType b)
  {
    const vtkIdType ids[2] = { a, b };
    lines_->InsertNextCell(2, ids);
  }
  void polyline(const std::vector<vtkIdType>& ids) { lines_->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data()); }
  void polygon(const std::vector<vtkIdType>& ids) { polys_->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data()); }

  template <typename Array>
  Array* cellArray(const char* name, int components = 1)
  {
    vtkNew<Array> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    data_->GetCellData()->AddArray(array);
    return array;
  }
  template <typename Array>
  Array* pointArray(const char* name, int components = 1)
  {
    vtkNew<Array> array;
    array->SetName(name);
    array->SetNumberOfComponents(components);
    data_->GetPointData()->AddArray(array);
    return array;
  }

  vtkSmartPointer<vtkPolyData> data() const { return data_; }

private:
  vtkSmartPointer<vtkPolyData> data_ = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points_;
  vtkNew<vtkCellArray> verts_;
  vtkNew<vtkCellArray> lines_;
  vtkNew<vtkCellArray> polys_;
};

void setBlock(vtkMultiBlockDataSet* parent, const std::string& name, vtkDataObject* block)
{
  const unsigned int index = parent->GetNumberOfBlocks();
  parent->SetBlock(index, block);
  parent->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), name.c_str());
}

void addFieldString(vtkDataObject* data, const char* name, const std::vector<std::string>& values)
{
  vtkNew<vtkStringArray> array;
  array->SetName(name);
  for (const std::string& value : values)
  {
    array->InsertNextValue(value);
  }
  data->GetFieldData()->AddArray(array);
}

void addFieldNumber(vtkDataObject* data, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  data->GetFieldData()->AddArray(array);
}

// Every piece of `block` names its coordinate system in its field data (`coordinates`): composite data sets keep
// no field data in a .vtm, their leaves do.
void nameCoordinates(vtkMultiBlockDataSet* block, const std::string& coordinates)
{
  for (unsigned int i = 0; i < block->GetNumberOfBlocks(); ++i)
  {
    if (vtkDataObject* leaf = block->GetBlock(i))
    {
      addFieldString(leaf, "coordinates", { coordinates });
    }
  }
}

// What every piece needs: the light, its view frame, the receiver.
struct Context
{
  const ProbeResult& probe;
  const FrameResult& frame;
  const Scene& scene;
  const Light& light;
  ProbeMap map; // the map the pixel's test read (its own view's, with views that partition the pixels)
  ProbeLightFrame lightFrame;
  ProbeReceiver receiver;
};

// A length to draw the receiver's normal with: a tenth of the way to the light.
double normalLength(const Context& context)
{
  const double distance = context.lightFrame.orthographic ? std::abs(context.receiver.depthLin)
                                                          : glm::length(context.lightFrame.eyeWs - context.receiver.position);
  return distance > 0.0 ? 0.1 * distance : 0.1;
}

vtkSmartPointer<vtkPolyData> lightPiece(const Context& context)
{
  PolyBuilder builder;
  const std::vector<glm::dvec3> outline = lightOutline(context.light);
  auto* lightXY = builder.pointArray<vtkDoubleArray>("light_xy", 2);
  if (!outline.empty())
  {
    std::vector<vtkIdType> ids;
    for (const glm::dvec3& p : outline)
    {
      ids.push_back(builder.point(p));
      const glm::dvec2 xy = context.lightFrame.lightFromWorld(p);
      lightXY->InsertNextTuple2(xy.x, xy.y);
    }
    builder.polygon(ids);
  }
  else
  {
    // Point, spot, directional: the view's eye (a directional light's eye is behind the scene) and its axis.
    const vtkIdType eye = builder.point(context.lightFrame.eyeWs);
    lightXY->InsertNextTuple2(0.0, 0.0);
    builder.vertex(eye);
    if (context.light.type == LightType::Directional || context.light.type == LightType::Spot)
    {
      const vtkIdType tip = builder.point(context.lightFrame.eyeWs + context.lightFrame.axisWs * normalLength(context));
      lightXY->InsertNextTuple2(0.0, 0.0);
      builder.line(eye, tip);
    }
  }
  vtkSmartPointer<vtkPolyData> data = builder.data();
  const char* types[] = { "area", "point", "directional", "spot" };
  addFieldString(data, "light_type", { types[static_cast<int>(context.light.type)] });
  addFieldNumber(data, "light_size", context.light.size);
  return data;
}

vtkSmartPointer<vtkPolyData> receiverPiece(const Context& context)
{
  PolyBuilder builder;
  auto* kind = builder.cellArray<vtkIntArray>("kind"); // 0 the point, 1 its normal
  auto* normal = builder.pointArray<vtkDoubleArray>("normal", 3);
  const vtkIdType point = builder.point(context.receiver.position);
  const glm::dvec3& n = context.receiver.normal;
  normal->InsertNextTuple3(n.x, n.y, n.z);
  builder.vertex(point);
  kind->InsertNextValue(0);
  const vtkIdType tip = builder.point(context.receiver.position + n * normalLength(context));
  normal->InsertNextTuple3(n.x, n.y, n.z);
  builder.line(point, tip);
  kind->InsertNextValue(1);
  vtkSmartPointer<vtkPolyData> data = builder.data();
  const ProbeResult& probe = context.probe;
  addFieldString(data, "technique", { probe.technique });
  addFieldString(data, "twin", { probe.outcome.twin });
  addFieldString(data, "ambiguity", { probe.outcome.ambiguity });
  addFieldNumber(data, "pixel_x", probe.pixel.x);
  addFieldNumber(data, "pixel_y", probe.pixel.y);
  addFieldNumber(data, "gpu_visibility", probe.gpuVisibility);
  addFieldNumber(data, "twin_visibility", probe.outcome.visibility);
  addFieldNumber(data, "tolerance", probe.outcome.tolerance);
  addFieldNumber(data, "receiver_depth", context.receiver.depthLin);
  if (context.receiver.bias)
  {
    addFieldNumber(data, "depth_bias", *context.receiver.bias);
  }
  return data;
}

vtkSmartPointer<vtkPolyData> raysToLightPiece(const Context& context)
{
  PolyBuilder builder;
  auto* target = builder.cellArray<vtkIntArray>("target"); // 0 the light's centre, 1 a corner / rim point
  const vtkIdType receiver = builder.point(context.receiver.position);
  // A directional light's rays are parallel: one back along its direction to the eye's plane.
  const glm::dvec3 centre = context.light.type == LightType::Directional
    ? context.receiver.position - context.lightFrame.axisWs * context.receiver.depthLin
    : context.lightFrame.eyeWs;
  builder.line(receiver, builder.point(centre));
  target->InsertNextValue(0);
  const std::vector<glm::dvec3> outline = lightOutline(context.light, 8);
  for (const glm::dvec3& corner : outline)
  {
    builder.line(receiver, builder.point(corner));
    target->InsertNextValue(1);
  }
  return builder.data();
}

vtkSmartPointer<vtkPolyData> raysToSamplesPiece(const Context& context)
{
  PolyBuilder builder;
  auto* blocked = builder.cellArray<vtkUnsignedCharArray>("blocked");
  auto* complexity = builder.cellArray<vtkIntArray>("depth_complexity");
  const auto& samples = context.probe.record.lightSamples;
  if (!samples.empty())
  {
    const vtkIdType receiver = builder.point(context.receiver.position);
    for (const ProbeLightSample& sample : samples)
    {
      builder.line(receiver, builder.point(context.lightFrame.worldFromLight(sample.position)));
      blocked->InsertNextValue(sample.blocked ? 1 : 0);
      complexity->InsertNextValue(sample.depthComplexity);
    }
  }
  return builder.data();
}

// Each kernel rectangle back-projected through the light view: the frustum of rays it covers, from the map's near
// depth to the receiver's, as six quads.
vtkSmartPointer<vtkPolyData> kernelFrustumPiece(const Context& context)
{
  PolyBuilder builder;
  auto* index = builder.cellArray<vtkIntArray>("kernel_index");
  auto* roleId = builder.cellArray<vtkIntArray>("role_id");
  auto* role = builder.cellArray<vtkStringArray>("role");
  if (context.map.view == nullptr)
  {
    return builder.data();
  }
  const LightView& view = *context.map.view;
  const std::vector<std::string> roles = kernelRoleLabels(context.probe.record);
  const double nearDepth = view.nearDepth;
  const double farDepth = context.receiver.depthLin;
  // Corners counter-clockwise in the map; quads of the near cap, the far cap and the four sides.
  static const int faces[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 },
    { 3, 0, 4, 7 } };
  for (std::size_t k = 0; k < context.probe.record.kernels.size(); ++k)
  {
    const ProbeKernel& kernel = context.probe.record.kernels[k];
    const glm::dvec2 corners[4] = { kernel.lo, { kernel.hi.x, kernel.lo.y }, kernel.hi, { kernel.lo.x, kernel.hi.y } };
    // Points 0-3 the near cap, 4-7 the far cap, each in the order lo, (hi.x, lo.y), hi, (lo.x, hi.y).
    vtkIdType ids[8];
    for (int c = 0; c < 8; ++c)
    {
      ids[c] = builder.point(worldFromTexel(view, corners[c % 4], c < 4 ? nearDepth : farDepth));
    }
    for (const auto& face : faces)
    {
      builder.polygon({ ids[face[0]], ids[face[1]], ids[face[2]], ids[face[3]] });
      index->InsertNextValue(static_cast<int>(k));
      roleId->InsertNextValue(labelCode(roles, kernel.role));
      role->InsertNextValue(kernel.role);
    }
  }
  return builder.data();
}

vtkSmartPointer<vtkMultiBlockDataSet> worldBlock(const Context& context)
{
  auto block = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  setBlock(block, "light", lightPiece(context));
  setBlock(block, "receiver", receiverPiece(context));
  setBlock(block, "rays_to_light", raysToLightPiece(context));
  setBlock(block, "rays_to_samples", raysToSamplesPiece(context));
  setBlock(block, "kernel_frustum", kernelFrustumPiece(context));
  nameCoordinates(block, "world units (the scene's)");
  return block;
}

template <typename Array, typename T>
void addCellImageArray(vtkDataSet* image, const char* name, const Image<T>& values)
{
  vtkNew<Array> array;
  array->SetName(name);
  array->SetNumberOfComponents(1);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.pixelCount()));
  // Image and vtkImageData both store rows bottom first, x fastest.
  for (std::size_t i = 0; i < values.pixelCount(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values.data[i]);
  }
  image->GetCellData()->AddArray(array);
}

// A shadow-map position (continuous texel coordinates) in world space, on the plane through the receiver
// perpendicular to the light's axis; the texel position itself where the frame has no map.
glm::dvec3 mapPoint(const Context& context, const glm::dvec2& uvTexels)
{
  if (context.map.view == nullptr)
  {
    return { uvTexels.x, uvTexels.y, 0.0 };
  }
  return worldFromTexel(*context.map.view, uvTexels, context.receiver.depthLin);
}

// The shadow-map block's points: world positions (mapPoint) with their texel coordinates alongside.
class MapPolyBuilder
{
public:
  explicit MapPolyBuilder(const Context& context)
    : context_(context)
    , texelUv_(builder_.pointArray<vtkDoubleArray>("texel_uv", 2))
  {
  }
  vtkIdType point(const glm::dvec2& uvTexels)
  {
    texelUv_->InsertNextTuple2(uvTexels.x, uvTexels.y);
    return builder_.point(mapPoint(context_, uvTexels));
  }
  PolyBuilder& builder() { return builder_; }

private:
  const Context& context_;
  PolyBuilder builder_;
  vtkDoubleArray* texelUv_;
};

constexpr const char* kMapCoordinates = "world units: shadow-map texels placed on the plane through the receiver "
  "perpendicular to the light's axis (texel (u, v) at the light view's ray through it, at the receiver's linear "
  "depth); point array texel_uv holds their texel coordinates";

vtkSmartPointer<vtkStructuredGrid> cropPiece(const Context& context)
{
  auto image = vtkSmartPointer<vtkStructuredGrid>::New();
  const ImageF* depth = context.map.depth;
  if (depth == nullptr || context.map.view == nullptr)
  {
    return image;
  }
  const TexelRect crop = probeShadowMapCrop(context.probe.record, context.receiver.uvTexels, depth->width);
  if (crop.empty())
  {
    return image;
  }
  const ProbeCropArrays arrays = probeCropArrays(context.probe.record, *depth, crop);
  // One cell per texel: points at texel corners, so cell (i, j) spans exactly [i, i + 1] x [j, j + 1] in the
  // map's continuous texel coordinates, as the kernels' and nodes' rectangles do; placed in world space.
  image->SetDimensions(crop.size.x + 1, crop.size.y + 1, 1);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkDoubleArray> texelUv;
  texelUv->SetName("texel_uv");
  texelUv->SetNumberOfComponents(2);
  for (int j = 0; j <= crop.size.y; ++j)
  {
    for (int i = 0; i <= crop.size.x; ++i)
    {
      const glm::dvec2 uv(crop.lo.x + i, crop.lo.y + j);
      const glm::dvec3 p = mapPoint(context, uv);
      points->InsertNextPoint(p.x, p.y, p.z);
      texelUv->InsertNextTuple2(uv.x, uv.y);
    }
  }
  image->SetPoints(points);
  image->GetPointData()->AddArray(texelUv);
  addFieldNumber(image, "texel_lo_x", crop.lo.x);
  addFieldNumber(image, "texel_lo_y", crop.lo.y);
  addCellImageArray<vtkFloatArray>(image, "depth", arrays.depth);
  addCellImageArray<vtkUnsignedCharArray>(image, "read", arrays.read);
  addCellImageArray<vtkUnsignedCharArray>(image, "compared", arrays.compared);
  addCellImageArray<vtkUnsignedCharArray>(image, "occluding", arrays.occluding);
  addCellImageArray<vtkFloatArray>(image, "weight", arrays.weight);
  addCellImageArray<vtkIntArray>(image, "visited_level", arrays.visitedLevel);
  image->GetCellData()->SetActiveScalars("depth");
  addFieldNumber(image, "shadow_map_size", depth->width);
  addFieldNumber(image, "far_depth", context.map.view->farDepth);
  addFieldString(image, "map", { context.map.exportName });
  if (!context.map.label.empty())
  {
    addFieldString(image, "view", { context.map.label });
  }
  return image;
}

void addRectangle(MapPolyBuilder& builder, const glm::dvec2& lo, const glm::dvec2& hi)
{
  builder.builder().polygon({ builder.point({ lo.x, lo.y }), builder.point({ hi.x, lo.y }), builder.point({ hi.x, hi.y }),
    builder.point({ lo.x, hi.y }) });
}

vtkSmartPointer<vtkPolyData> visitedNodesPiece(const Context& context)
{
  MapPolyBuilder mapBuilder(context);
  PolyBuilder& builder = mapBuilder.builder();
  auto* level = builder.cellArray<vtkIntArray>("level");
  auto* decisionCode = builder.cellArray<vtkIntArray>("decision_code");
  auto* decision = builder.cellArray<vtkStringArray>("decision");
  auto* structure = builder.cellArray<vtkStringArray>("structure");
  auto* minDepth = builder.cellArray<vtkDoubleArray>("min_depth");
  auto* maxDepth = builder.cellArray<vtkDoubleArray>("max_depth");
  const std::vector<std::string> decisions = nodeDecisionLabels(context.probe.record);
  for (const ProbeNode& node : context.probe.record.nodes)
  {
    addRectangle(mapBuilder, glm::dvec2(node.lo), glm::dvec2(node.hi) + 1.0);
    level->InsertNextValue(node.level);
    decisionCode->InsertNextValue(labelCode(decisions, node.decision));
    decision->InsertNextValue(node.decision);
    structure->InsertNextValue(node.structure);
    minDepth->InsertNextValue(node.minDepth);
    maxDepth->InsertNextValue(node.maxDepth);
  }
  vtkSmartPointer<vtkPolyData> data = builder.data();
  addFieldString(data, "decision_labels", decisions); // decision_code indexes this list
  return data;
}

vtkSmartPointer<vtkPolyData> kernelsPiece(const Context& context)
{
  MapPolyBuilder mapBuilder(context);
  PolyBuilder& builder = mapBuilder.builder();
  auto* roleId = builder.cellArray<vtkIntArray>("role_id");
  auto* role = builder.cellArray<vtkStringArray>("role");
  auto* label = builder.cellArray<vtkStringArray>("label");
  auto* source = builder.cellArray<vtkStringArray>("source");
  const std::vector<std::string> roles = kernelRoleLabels(context.probe.record);
  for (const ProbeKernel& kernel : context.probe.record.kernels)
  {
    addRectangle(mapBuilder, kernel.lo, kernel.hi);
    roleId->InsertNextValue(labelCode(roles, kernel.role));
    role->InsertNextValue(kernel.role);
    label->InsertNextValue(kernel.label);
    source->InsertNextValue(kernel.source);
  }
  vtkSmartPointer<vtkPolyData> data = builder.data();
  addFieldString(data, "role_labels", roles);
  return data;
}

// The pixel's footprint in the map (Probe.cpp recordSamplingError), a closed polygon.
vtkSmartPointer<vtkPolyData> pixelFootprintPiece(const Context& context)
{
  MapPolyBuilder mapBuilder(context);
  PolyBuilder& builder = mapBuilder.builder();
  auto* role = builder.cellArray<vtkStringArray>("role");
  for (const ProbeMapPolygon& polygon : context.probe.record.mapPolygons)
  {
    std::vector<vtkIdType> ids;
    for (const glm::dvec2& point : polygon.points)
    {
      ids.push_back(mapBuilder.point(point));
    }
    builder.polygon(ids);
    role->InsertNextValue(polygon.role);
  }
  return builder.data();
}

vtkSmartPointer<vtkPolyData> receiverTexelPiece(const Context& context)
{
  MapPolyBuilder mapBuilder(context);
  if (context.receiver.uvTexels)
  {
    mapBuilder.builder().vertex(mapBuilder.point(*context.receiver.uvTexels));
  }
  return mapBuilder.builder().data();
}

vtkSmartPointer<vtkMultiBlockDataSet> shadowMapBlock(const Context& context)
{
  auto block = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  setBlock(block, "crop", cropPiece(context));
  setBlock(block, "visited_nodes", visitedNodesPiece(context));
  setBlock(block, "kernels", kernelsPiece(context));
  setBlock(block, "receiver", receiverTexelPiece(context));
  setBlock(block, "pixel_footprint", pixelFootprintPiece(context));
  nameCoordinates(block, kMapCoordinates);
  return block;
}

vtkSmartPointer<vtkPolyData> lightOutlinePiece(const Context& context)
{
  PolyBuilder builder;
  auto* lightXY = builder.pointArray<vtkDoubleArray>("light_xy", 2);
  std::vector<vtkIdType> ids;
  for (const glm::dvec3& p : lightOutline(context.light))
  {
    ids.push_back(builder.point(p));
    const glm::dvec2 xy = context.lightFrame.lightFromWorld(p);
    lightXY->InsertNextTuple2(xy.x, xy.y);
  }
  if (!ids.empty())
  {
    ids.push_back(ids.front());
    builder.polyline(ids);
  }
  return builder.data();
}

vtkSmartPointer<vtkPolyData> lightPolygonsPiece(const Context& context)
{
  PolyBuilder builder;
  auto* lightXY = builder.pointArray<vtkDoubleArray>("light_xy", 2);
  auto* signedArea = builder.cellArray<vtkDoubleArray>("signed_area");
  auto* roleId = builder.cellArray<vtkIntArray>("role_id");
  auto* role = builder.cellArray<vtkStringArray>("role");
  const std::vector<std::string> roles = polygonRoleLabels(context.probe.record);
  for (const ProbeLightPolygon& polygon : context.probe.record.lightPolygons)
  {
    if (polygon.points.size() < 3)
    {
      continue;
    }
    std::vector<vtkIdType> ids;
    for (const glm::dvec2& xy : polygon.points)
    {
      ids.push_back(builder.point(context.lightFrame.worldFromLight(xy)));
      lightXY->InsertNextTuple2(xy.x, xy.y);
    }
    builder.polygon(ids);
    signedArea->InsertNextValue(polygon.signedArea);
    roleId->InsertNextValue(labelCode(roles, polygon.role));
    role->InsertNextValue(polygon.role);
  }
  vtkSmartPointer<vtkPolyData> data = builder.data();
  addFieldString(data, "role_labels", roles);
  return data;
}

vtkSmartPointer<vtkPolyData> contourEdgesPiece(const Context& context)
{
  PolyBuilder builder;
  auto* lightXY = builder.pointArray<vtkDoubleArray>("light_xy", 2);
  auto* texelXY = builder.pointArray<vtkDoubleArray>("texel_xy", 2); // the edge's ends in the shadow map
  auto* signedArea = builder.cellArray<vtkDoubleArray>("signed_area");
  for (const ProbeContourEdge& edge : context.probe.record.contourEdges)
  {
    const vtkIdType a = builder.point(context.lightFrame.worldFromLight(edge.lightA));
    lightXY->InsertNextTuple2(edge.lightA.x, edge.lightA.y);
    texelXY->InsertNextTuple2(edge.a.x, edge.a.y);
    const vtkIdType b = builder.point(context.lightFrame.worldFromLight(edge.lightB));
    lightXY->InsertNextTuple2(edge.lightB.x, edge.lightB.y);
    texelXY->InsertNextTuple2(edge.b.x, edge.b.y);
    builder.line(a, b);
    signedArea->InsertNextValue(edge.signedArea);
  }
  return builder.data();
}

vtkSmartPointer<vtkPolyData> lightSamplesPiece(const Context& context)
{
  PolyBuilder builder;
  auto* lightXY = builder.pointArray<vtkDoubleArray>("light_xy", 2);
  auto* blocked = builder.pointArray<vtkUnsignedCharArray>("blocked");
  auto* complexity = builder.pointArray<vtkIntArray>("depth_complexity");
  for (const ProbeLightSample& sample : context.probe.record.lightSamples)
  {
    builder.vertex(builder.point(context.lightFrame.worldFromLight(sample.position)));
    lightXY->InsertNextTuple2(sample.position.x, sample.position.y);
    blocked->InsertNextValue(sample.blocked ? 1 : 0);
    complexity->InsertNextValue(sample.depthComplexity);
  }
  return builder.data();
}

vtkSmartPointer<vtkMultiBlockDataSet> lightPlaneBlock(const Context& context)
{
  auto block = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  setBlock(block, "light_outline", lightOutlinePiece(context));
  setBlock(block, "polygons", lightPolygonsPiece(context));
  setBlock(block, "contour_edges", contourEdgesPiece(context));
  setBlock(block, "light_samples", lightSamplesPiece(context));
  nameCoordinates(block, "world units, on the light's plane; point array light_xy holds the light coordinates (the "
    "light view's x, y from the light's centre)");
  return block;
}

} // namespace

vtkSmartPointer<vtkMultiBlockDataSet> probeDataSet(const ProbeResult& probe, const FrameResult& frame, const Scene& scene)
{
  const ProbeSetting setting = probeSetting(probe, frame, scene);
  const Context context{ probe, frame, scene, *setting.light, setting.map, setting.lightFrame, setting.receiver };
  auto root = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  setBlock(root, "world", worldBlock(context));
  setBlock(root, "shadow_map", shadowMapBlock(context));
  setBlock(root, "light_plane", lightPlaneBlock(context));
  return root;
}

} // namespace sl
