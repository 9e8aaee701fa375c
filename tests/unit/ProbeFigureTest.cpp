// probe.vtm and probe.png (probe/Probe.h: probeDataSet, probeFigure; probe/ProbeGeometry.h; vis/CanvasShapes.h)
// on a synthetic frame: an area light 5 units above a ground plane, a 2 x 2 quad caster at height 1, a 64^2
// shadow map rasterised here by intersecting each texel's ray with the two quads, and a hand-made record (texels,
// a kernel, nodes, light polygons, samples) whose every item has a known place in the output.
#include "vis/NumberText.h"
#include "probe/Probe.h"
#include "probe/ProbeFigure.h"
#include "probe/ProbeGeometry.h"

#include "io/ImageIO.h"
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "support/TempDir.h"
#include "vis/Canvas.h"
#include "vis/CanvasShapes.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkStructuredGrid.h>
#include <vtkFieldData.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLMultiBlockDataWriter.h>

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>

namespace sl
{
namespace
{

constexpr double kLightHeight = 5.0;
constexpr double kCasterHeight = 1.0;
constexpr double kCasterHalf = 1.0;
constexpr double kGroundHalf = 4.0;
constexpr int kMapSize = 64;

SceneObject horizontalQuad(const std::string& name, double height, double half, bool castShadows)
{
  SceneObject object;
  object.name = name;
  object.castShadows = castShadows;
  const float h = static_cast<float>(height);
  const float s = static_cast<float>(half);
  object.mesh.positions = { { -s, h, -s }, { s, h, -s }, { s, h, s }, { -s, h, s } };
  object.mesh.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
  object.mesh.indices = { 0, 2, 1, 0, 3, 2 };
  return object;
}

Scene syntheticScene()
{
  Scene scene;
  Light light;
  light.type = LightType::Area;
  light.shape = LightShape::Square;
  light.center = { 0.0, kLightHeight, 0.0 };
  light.normal = { 0.0, -1.0, 0.0 };
  light.up = { 0.0, 0.0, 1.0 };
  light.size = 1.0;
  scene.lights.push_back(light);
  scene.objects.push_back(horizontalQuad("caster", kCasterHeight, kCasterHalf, true));
  scene.objects.push_back(horizontalQuad("ground", 0.0, kGroundHalf, false));
  return scene;
}

// The light view fitted to ground receivers in x, z in [-3, 3].
LightView syntheticLightView(const Scene& scene)
{
  const int side = 16;
  ImageF position(side, side, 4, 0.0f);
  ImageF normal(side, side, 4, 0.0f);
  for (int y = 0; y < side; ++y)
  {
    for (int x = 0; x < side; ++x)
    {
      const float px = -3.0f + 6.0f * x / (side - 1);
      const float pz = -3.0f + 6.0f * y / (side - 1);
      const float p[4] = { px, 0.0f, pz, 1.0f };
      const float n[4] = { 0.0f, 1.0f, 0.0f, 1.0f };
      for (int c = 0; c < 4; ++c)
      {
        position.at(x, y, c) = p[c];
        normal.at(x, y, c) = n[c];
      }
    }
  }
  FocusSettings settings;
  settings.resolution = kMapSize;
  settings.lightFootprintWidth = scene.lights[0].size;
  return fitLightView(scene.lights[0], scene, position, normal, settings);
}

// The linear depth of the nearest quad along each texel centre's ray, found from the clip-space inverse (not
// through the code under test); empty texels hold 2 x far as the GPU's map does.
ImageF rasteriseShadowMap(const LightView& view)
{
  ImageF map(kMapSize, kMapSize, 1, static_cast<float>(2.0 * view.farDepth));
  const glm::dmat4 worldFromClip = glm::inverse(view.clipFromWorld);
  for (int j = 0; j < kMapSize; ++j)
  {
    for (int i = 0; i < kMapSize; ++i)
    {
      const glm::dvec2 ndc((i + 0.5) / kMapSize * 2.0 - 1.0, (j + 0.5) / kMapSize * 2.0 - 1.0);
      glm::dvec4 nearPoint = worldFromClip * glm::dvec4(ndc, -1.0, 1.0);
      glm::dvec4 farPoint = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
      const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w;
      const glm::dvec3 b = glm::dvec3(farPoint) / farPoint.w;
      for (const auto& [height, half] : { std::pair{ kCasterHeight, kCasterHalf }, std::pair{ 0.0, kGroundHalf } })
      {
        const glm::dvec3 hit = a + (b - a) * ((height - a.y) / (b.y - a.y));
        if (std::abs(hit.x) <= half && std::abs(hit.z) <= half)
        {
          map.at(i, j) = static_cast<float>(-(view.viewFromWorld * glm::dvec4(hit, 1.0)).z);
          break;
        }
      }
    }
  }
  return map;
}

// A 64 x 48 image with a colour per pixel that no marker uses (blue fixed at 90, red and green from x and y).
ImageU8 gradientImage()
{
  ImageU8 image(64, 48, 3);
  for (int y = 0; y < image.height; ++y)
  {
    for (int x = 0; x < image.width; ++x)
    {
      image.at(x, y, 0) = static_cast<std::uint8_t>(3 * x);
      image.at(x, y, 1) = static_cast<std::uint8_t>(5 * y);
      image.at(x, y, 2) = 90;
    }
  }
  return image;
}

double shoelace(const std::vector<glm::dvec2>& points)
{
  double twiceArea = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const glm::dvec2& p = points[i];
    const glm::dvec2& q = points[(i + 1) % points.size()];
    twiceArea += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twiceArea;
}

struct Synthetic
{
  Scene scene;
  FrameResult frame;
  ProbeResult probe;
  glm::dvec3 receiver{ 0.3, 0.0, 0.2 };
  std::set<std::pair<int, int>> occludingTexels;
  std::set<std::pair<int, int>> readTexels;
  std::set<std::pair<int, int>> comparedTexels;
};

Synthetic makeSynthetic(glm::ivec2 pixel = { 20, 30 })
{
  Synthetic s;
  s.scene = syntheticScene();
  const LightView view = syntheticLightView(s.scene);
  FrameResult& frame = s.frame;
  frame.technique = "hard";
  frame.resolution = { 64, 48 };
  frame.lightView = view;
  frame.lightSpace.push_back({ "shadow_map_depth", rasteriseShadowMap(view), "world units", "linear depth", {}, {} });
  frame.image = gradientImage();

  ProbeResult& probe = s.probe;
  probe.technique = "hard";
  probe.pixel = pixel;
  probe.gpuVisibility = 0.25;
  probe.outcome.evaluated = true;
  probe.outcome.visibility = 0.25;
  probe.outcome.tolerance = 1e-4;
  probe.outcome.twin = "synthetic record";
  ProbeRecorder recorder;
  const ShadowMapSample sample = projectToShadowMap(view, s.receiver);
  recorder.beginGroup("receiver");
  recorder.quantity("position", s.receiver, "world units", "test");
  recorder.quantity("normal", glm::dvec3(0.0, 1.0, 0.0), "", "test");
  recorder.quantity("shadow_map_position", sample.uvTexels, "texels", "test");
  recorder.quantity("receiver_depth", sample.depthLin, "linear depth", "test");
  recorder.quantity("depth_bias", 0.01, "linear depth", "test");
  recorder.beginGroup("filter");
  const glm::ivec2 centre(glm::floor(sample.uvTexels));
  for (int dy = -1; dy <= 1; ++dy)
  {
    for (int dx = -1; dx <= 1; ++dx)
    {
      const glm::ivec2 texel = centre + glm::ivec2(dx, dy);
      const bool occluding = (dx + dy + 2) % 2 == 0;
      recorder.texel({ texel, "filter tap", 4.0, sample.depthLin - 0.01, occluding, 1.0 / 9.0 });
      s.readTexels.insert({ texel.x, texel.y });
      s.comparedTexels.insert({ texel.x, texel.y });
      if (occluding)
      {
        s.occludingTexels.insert({ texel.x, texel.y });
      }
    }
  }
  // Read without a comparison (a blocker search's read, say).
  const glm::ivec2 readOnly = centre + glm::ivec2(3, 0);
  recorder.texel({ readOnly, "blocker search", 4.0, std::numeric_limits<double>::quiet_NaN(), false, 1.0 });
  s.readTexels.insert({ readOnly.x, readOnly.y });
  recorder.kernel({ "filter", glm::dvec2(centre - 1), glm::dvec2(centre + 2), "", "test" });
  recorder.node({ "hsm", 2, centre - 2, centre + 1, 4.0, 5.0, "descend" });
  recorder.node({ "hsm", 0, centre, centre, 4.0, 4.0, "umbra" });
  // Light polygons in light coordinates: one counter-clockwise, one clockwise.
  const std::vector<glm::dvec2> positive = { { -0.4, -0.4 }, { 0.1, -0.4 }, { 0.1, 0.2 } };
  const std::vector<glm::dvec2> negative = { { 0.2, 0.0 }, { 0.2, 0.45 }, { 0.45, 0.0 } };
  recorder.lightPolygon({ "micropatch", positive, shoelace(positive) });
  recorder.lightPolygon({ "micropatch", negative, shoelace(negative) });
  recorder.contourEdge({ { 1.0, 2.0 }, { 3.0, 4.0 }, { -0.3, 0.3 }, { 0.3, 0.3 }, 0.05 });
  recorder.lightSample({ { -0.25, -0.25 }, true, 1 });
  recorder.lightSample({ { 0.25, -0.25 }, false, 0 });
  recorder.lightSample({ { 0.25, 0.25 }, true, 2 });
  recorder.lightSample({ { -0.25, 0.25 }, false, 0 });
  probe.record = recorder.record();
  return s;
}

std::string blockName(vtkMultiBlockDataSet* blocks, unsigned int index)
{
  vtkInformation* metaData = blocks->HasMetaData(index) ? blocks->GetMetaData(index) : nullptr;
  const char* name = metaData != nullptr ? metaData->Get(vtkCompositeDataSet::NAME()) : nullptr;
  return name != nullptr ? name : "";
}

vtkDataObject* piece(vtkMultiBlockDataSet* root, const std::string& block, const std::string& name)
{
  for (unsigned int b = 0; b < root->GetNumberOfBlocks(); ++b)
  {
    if (blockName(root, b) != block)
    {
      continue;
    }
    auto* children = vtkMultiBlockDataSet::SafeDownCast(root->GetBlock(b));
    for (unsigned int c = 0; children != nullptr && c < children->GetNumberOfBlocks(); ++c)
    {
      if (blockName(children, c) == name)
      {
        return children->GetBlock(c);
      }
    }
  }
  return nullptr;
}

enum class Writer
{
  ShadowLab, // io/ImageIO.h writeVtm, what `shadowlab probe` writes
  Vtk        // vtkXMLMultiBlockDataWriter
};

vtkSmartPointer<vtkMultiBlockDataSet> roundTrip(vtkMultiBlockDataSet* blocks, const std::filesystem::path& dir, Writer writer)
{
  const std::filesystem::path file = dir / (writer == Writer::Vtk ? "vtk.vtm" : "probe.vtm");
  if (writer == Writer::Vtk)
  {
    vtkNew<vtkXMLMultiBlockDataWriter> xmlWriter;
    xmlWriter->SetInputData(blocks);
    xmlWriter->SetFileName(file.string().c_str());
    EXPECT_EQ(xmlWriter->Write(), 1);
  }
  else
  {
    writeVtm(file, blocks);
  }
  vtkNew<vtkXMLMultiBlockDataReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  auto result = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  result->ShallowCopy(reader->GetOutput());
  return result;
}

glm::dvec3 pointOf(vtkPolyData* data, vtkIdType id)
{
  double p[3];
  data->GetPoint(id, p);
  return { p[0], p[1], p[2] };
}

TEST(ProbeDataSet, RoundTripsThroughXmlWithItsBlocksAndArrays)
{
  const Synthetic s = makeSynthetic();
  const vtkSmartPointer<vtkMultiBlockDataSet> blocks = probeDataSet(s.probe, s.frame, s.scene);
  const test::TempDir dir;
  for (const Writer writer : { Writer::ShadowLab, Writer::Vtk })
  {
    SCOPED_TRACE(writer == Writer::Vtk ? "vtkXMLMultiBlockDataWriter" : "writeVtm");
    const auto read = roundTrip(blocks, dir.path(), writer);
    ASSERT_EQ(read->GetNumberOfBlocks(), 3u);
    EXPECT_EQ(blockName(read, 0), "world");
    EXPECT_EQ(blockName(read, 1), "shadow_map");
    EXPECT_EQ(blockName(read, 2), "light_plane");
    const std::map<std::string, std::vector<std::string>> pieces = {
      { "world", { "light", "receiver", "rays_to_light", "rays_to_samples", "kernel_frustum" } },
      { "shadow_map", { "crop", "visited_nodes", "kernels", "receiver" } },
      { "light_plane", { "light_outline", "polygons", "contour_edges", "light_samples" } },
    };
    for (const auto& [block, names] : pieces)
    {
      for (const std::string& name : names)
      {
        EXPECT_NE(piece(read, block, name), nullptr) << block << "/" << name;
      }
    }
    auto* crop = vtkStructuredGrid::SafeDownCast(piece(read, "shadow_map", "crop"));
    ASSERT_NE(crop, nullptr);
    for (const char* array : { "depth", "read", "compared", "occluding", "weight", "visited_level" })
    {
      EXPECT_NE(crop->GetCellData()->GetArray(array), nullptr) << array;
    }
    auto* nodes = vtkPolyData::SafeDownCast(piece(read, "shadow_map", "visited_nodes"));
    ASSERT_NE(nodes, nullptr);
    EXPECT_EQ(nodes->GetNumberOfCells(), 2);
    ASSERT_NE(nodes->GetCellData()->GetArray("level"), nullptr);
    EXPECT_EQ(nodes->GetCellData()->GetArray("level")->GetTuple1(0), 2.0);
    ASSERT_NE(nodes->GetCellData()->GetArray("decision_code"), nullptr);
    EXPECT_EQ(nodes->GetCellData()->GetArray("decision_code")->GetTuple1(1), 1.0); // "umbra", second seen
    auto* samples = vtkPolyData::SafeDownCast(piece(read, "light_plane", "light_samples"));
    ASSERT_NE(samples, nullptr);
    ASSERT_EQ(samples->GetNumberOfPoints(), 4);
    vtkDataArray* blocked = samples->GetPointData()->GetArray("blocked");
    ASSERT_NE(blocked, nullptr);
    for (vtkIdType i = 0; i < 4; ++i)
    {
      EXPECT_EQ(blocked->GetTuple1(i), s.probe.record.lightSamples[i].blocked ? 1.0 : 0.0) << "sample " << i;
    }
    // The kernel's frustum: 6 faces; its far cap at the receiver's depth projects back onto the kernel's corners.
    auto* frustum = vtkPolyData::SafeDownCast(piece(read, "world", "kernel_frustum"));
    ASSERT_NE(frustum, nullptr);
    EXPECT_EQ(frustum->GetNumberOfCells(), 6);
    const ProbeKernel& kernel = s.probe.record.kernels.front();
    const ShadowMapSample corner = projectToShadowMap(*s.frame.lightView, pointOf(frustum, 4));
    EXPECT_NEAR(corner.uvTexels.x, kernel.lo.x, 1e-9);
    EXPECT_NEAR(corner.uvTexels.y, kernel.lo.y, 1e-9);
    EXPECT_NEAR(corner.depthLin, projectToShadowMap(*s.frame.lightView, s.receiver).depthLin, 1e-9);
  }
}

TEST(ProbeDataSet, CropArraysMarkExactlyTheRecordedTexels)
{
  const Synthetic s = makeSynthetic();
  const test::TempDir dir;
  const auto read = roundTrip(probeDataSet(s.probe, s.frame, s.scene), dir.path(), Writer::ShadowLab);
  auto* crop = vtkStructuredGrid::SafeDownCast(piece(read, "shadow_map", "crop"));
  ASSERT_NE(crop, nullptr);
  int dims[3];
  crop->GetDimensions(dims);
  // The crop's first texel: its first point's texel coordinates.
  vtkDataArray* texelUv = crop->GetPointData()->GetArray("texel_uv");
  ASSERT_NE(texelUv, nullptr);
  const double origin[2] = { texelUv->GetComponent(0, 0), texelUv->GetComponent(0, 1) };
  const int width = dims[0] - 1; // one cell per texel
  const int height = dims[1] - 1;
  ASSERT_GT(width, 3);
  ASSERT_GT(height, 3);
  vtkDataArray* occluding = crop->GetCellData()->GetArray("occluding");
  vtkDataArray* readArray = crop->GetCellData()->GetArray("read");
  vtkDataArray* compared = crop->GetCellData()->GetArray("compared");
  vtkDataArray* depth = crop->GetCellData()->GetArray("depth");
  vtkDataArray* level = crop->GetCellData()->GetArray("visited_level");
  ASSERT_TRUE(occluding && readArray && compared && depth && level);
  const ImageF& map = s.frame.lightSpace.front().image;
  const glm::ivec2 centre(glm::floor(projectToShadowMap(*s.frame.lightView, s.receiver).uvTexels));
  std::size_t occludingSeen = 0;
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const vtkIdType cell = y * width + x;
      const std::pair<int, int> texel{ int(origin[0]) + x, int(origin[1]) + y };
      EXPECT_EQ(occluding->GetTuple1(cell), s.occludingTexels.count(texel) ? 1.0 : 0.0) << texel.first << "," << texel.second;
      EXPECT_EQ(readArray->GetTuple1(cell), s.readTexels.count(texel) ? 1.0 : 0.0) << texel.first << "," << texel.second;
      EXPECT_EQ(compared->GetTuple1(cell), s.comparedTexels.count(texel) ? 1.0 : 0.0) << texel.first << "," << texel.second;
      EXPECT_EQ(depth->GetTuple1(cell), map.at(texel.first, texel.second));
      // The finest visited node over each texel: the single umbra texel at level 0 inside the level-2 block.
      const glm::ivec2 offset = glm::ivec2(texel.first, texel.second) - centre;
      const double expectedLevel = offset == glm::ivec2(0) ? 0.0 : (offset.x >= -2 && offset.x <= 1 && offset.y >= -2 && offset.y <= 1) ? 2.0 : -1.0;
      EXPECT_EQ(level->GetTuple1(cell), expectedLevel) << texel.first << "," << texel.second;
      occludingSeen += occluding->GetTuple1(cell) != 0.0 ? 1 : 0;
    }
  }
  EXPECT_EQ(occludingSeen, s.occludingTexels.size()); // every recorded occluding texel lies in the crop
}

// The bounds of every non-empty piece of `blocks`, by block.
std::map<std::string, std::vector<std::pair<std::string, std::array<double, 6>>>> probeDataSetPieceBounds(
  vtkMultiBlockDataSet* blocks)
{
  std::map<std::string, std::vector<std::pair<std::string, std::array<double, 6>>>> bounds;
  for (unsigned int b = 0; b < blocks->GetNumberOfBlocks(); ++b)
  {
    auto* block = vtkMultiBlockDataSet::SafeDownCast(blocks->GetBlock(b));
    for (unsigned int p = 0; block != nullptr && p < block->GetNumberOfBlocks(); ++p)
    {
      auto* data = vtkDataSet::SafeDownCast(block->GetBlock(p));
      if (data == nullptr || data->GetNumberOfPoints() == 0)
      {
        continue;
      }
      std::array<double, 6> box{};
      data->GetBounds(box.data());
      bounds[blockName(blocks, b)].push_back({ blockName(block, p), box });
    }
  }
  return bounds;
}

TEST(ProbeDataSet, EveryBlockIsInWorldUnitsAndOverlapsTheScene)
{
  // issue 31: the shadow_map block was in texel units (0..64 here, 0..2048 in a real map) and landed far from the
  // world and light_plane blocks in ParaView. Now every piece lies within the scene's reach: the scene's bounds
  // (ground 8 x 8 at y = 0, light at y = 5) grown by a margin, and the crop sits under the receiver.
  const Synthetic s = makeSynthetic();
  const test::TempDir dir;
  const auto read = roundTrip(probeDataSet(s.probe, s.frame, s.scene), dir.path(), Writer::ShadowLab);
  const auto bounds = probeDataSetPieceBounds(read);
  ASSERT_EQ(bounds.count("shadow_map"), 1u);
  const double sceneLo[3] = { -kGroundHalf, 0.0, -kGroundHalf };
  const double sceneHi[3] = { kGroundHalf, kLightHeight, kGroundHalf };
  const double margin = 1.0;
  for (const auto& [block, pieces] : bounds)
  {
    for (const auto& [name, box] : pieces)
    {
      for (int axis = 0; axis < 3; ++axis)
      {
        EXPECT_GE(box[2 * axis], sceneLo[axis] - margin) << block << "/" << name << " axis " << axis;
        EXPECT_LE(box[2 * axis + 1], sceneHi[axis] + margin) << block << "/" << name << " axis " << axis;
      }
      auto* data = vtkDataSet::SafeDownCast(piece(read, block, name));
      ASSERT_NE(data, nullptr);
      auto* coordinates = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("coordinates"));
      ASSERT_NE(coordinates, nullptr) << block << "/" << name << " names no coordinate system";
      EXPECT_EQ(coordinates->GetValue(0).rfind("world units", 0), 0u) << coordinates->GetValue(0);
    }
  }
  // The crop and the receiver's texel lie on the receiver's plane (the ground, y = 0) around the receiver.
  const auto crop = std::find_if(bounds.at("shadow_map").begin(), bounds.at("shadow_map").end(),
    [](const auto& entry) { return entry.first == "crop"; });
  ASSERT_NE(crop, bounds.at("shadow_map").end());
  EXPECT_NEAR(crop->second[2], 0.0, 1e-9);
  EXPECT_NEAR(crop->second[3], 0.0, 1e-9);
  EXPECT_LE(crop->second[0], s.receiver.x);
  EXPECT_GE(crop->second[1], s.receiver.x);
  EXPECT_LE(crop->second[4], s.receiver.z);
  EXPECT_GE(crop->second[5], s.receiver.z);
  auto* receiverTexel = vtkPolyData::SafeDownCast(piece(read, "shadow_map", "receiver"));
  ASSERT_NE(receiverTexel, nullptr);
  ASSERT_EQ(receiverTexel->GetNumberOfPoints(), 1);
  const glm::dvec3 placed = pointOf(receiverTexel, 0);
  EXPECT_NEAR(glm::length(placed - s.receiver), 0.0, 1e-9) << placed.x << "," << placed.y << "," << placed.z;
  // Kernels keep their texel coordinates alongside.
  auto* kernels = vtkPolyData::SafeDownCast(piece(read, "shadow_map", "kernels"));
  ASSERT_NE(kernels, nullptr);
  vtkDataArray* texelUv = kernels->GetPointData()->GetArray("texel_uv");
  ASSERT_NE(texelUv, nullptr);
  EXPECT_EQ(texelUv->GetComponent(0, 0), s.probe.record.kernels.front().lo.x);
  EXPECT_EQ(texelUv->GetComponent(0, 1), s.probe.record.kernels.front().lo.y);
}

TEST(ProbeDataSet, WorldReceiverAndLightPlanePolygonsMatchTheRecord)
{
  const Synthetic s = makeSynthetic();
  const test::TempDir dir;
  const auto read = roundTrip(probeDataSet(s.probe, s.frame, s.scene), dir.path(), Writer::ShadowLab);
  auto* receiver = vtkPolyData::SafeDownCast(piece(read, "world", "receiver"));
  ASSERT_NE(receiver, nullptr);
  ASSERT_GE(receiver->GetNumberOfPoints(), 1);
  const glm::dvec3 point = pointOf(receiver, 0);
  EXPECT_EQ(point, s.receiver) << point.x << "," << point.y << "," << point.z;

  // The square light's corners, in world space.
  auto* light = vtkPolyData::SafeDownCast(piece(read, "world", "light"));
  ASSERT_NE(light, nullptr);
  ASSERT_EQ(light->GetNumberOfPoints(), 4);
  for (vtkIdType i = 0; i < 4; ++i)
  {
    const glm::dvec3 corner = pointOf(light, i);
    EXPECT_NEAR(corner.y, kLightHeight, 1e-12);
    EXPECT_NEAR(std::abs(corner.x), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(corner.z), 0.5, 1e-12);
  }

  auto* polygons = vtkPolyData::SafeDownCast(piece(read, "light_plane", "polygons"));
  ASSERT_NE(polygons, nullptr);
  ASSERT_EQ(polygons->GetNumberOfCells(), 2);
  vtkDataArray* signedArea = polygons->GetCellData()->GetArray("signed_area");
  ASSERT_NE(signedArea, nullptr);
  const glm::dmat4& viewFromWorld = s.frame.lightView->viewFromWorld;
  for (vtkIdType c = 0; c < 2; ++c)
  {
    vtkNew<vtkIdList> ids;
    polygons->GetCellPoints(c, ids);
    std::vector<glm::dvec2> lightXY;
    glm::dvec3 twiceWorldArea(0.0); // sum of p_k x p_k+1: twice the vector area
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      const glm::dvec3 p = pointOf(polygons, ids->GetId(k));
      twiceWorldArea += glm::cross(p, pointOf(polygons, ids->GetId((k + 1) % ids->GetNumberOfIds())));
      const glm::dvec4 pLs = viewFromWorld * glm::dvec4(p, 1.0);
      EXPECT_NEAR(pLs.z, 0.0, 1e-12) << "a light-plane point off the light's plane";
      lightXY.emplace_back(pLs.x, pLs.y);
    }
    const double recorded = s.probe.record.lightPolygons[std::size_t(c)].signedArea;
    EXPECT_NEAR(shoelace(lightXY), recorded, 1e-12) << "polygon " << c;
    EXPECT_EQ(signedArea->GetTuple1(c), recorded);
    // The world-space polygon has the recorded area too (the light frame is rigid).
    EXPECT_NEAR(0.5 * glm::length(twiceWorldArea), std::abs(recorded), 1e-12);
  }
  EXPECT_LT(signedArea->GetTuple1(1), 0.0);
}

TEST(ProbeSection, HorizontalQuadCasterCutsAtItsHeight)
{
  const Synthetic s = makeSynthetic();
  const Light& light = s.scene.lights[0];
  const ProbeSection section = probeSection(light.center, light.normal, s.receiver, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_FALSE(section.usesReceiverNormal);
  EXPECT_NEAR(section.towardLight.y, 1.0, 1e-12);
  // The plane holds the light's centre, the receiver and the vertical axis: across = the receiver's horizontal
  // direction.
  const glm::dvec3 horizontal = glm::normalize(glm::dvec3(s.receiver.x, 0.0, s.receiver.z));
  EXPECT_NEAR(glm::dot(section.across, horizontal), 1.0, 1e-12);
  // The square |x|, |z| <= 1 cut along that direction: |t| <= 1 / max(|dir.x|, |dir.z|).
  const double reach = kCasterHalf / std::max(std::abs(horizontal.x), std::abs(horizontal.z));
  double casterMin = 1e300;
  double casterMax = -1e300;
  std::size_t groundSegments = 0;
  for (const SectionSegment& segment : sceneSection(s.scene, section))
  {
    const double expectedY = (segment.object == 0 ? kCasterHeight : 0.0) - kLightHeight;
    EXPECT_NEAR(segment.a.y, expectedY, 1e-12);
    EXPECT_NEAR(segment.b.y, expectedY, 1e-12);
    if (segment.object == 0)
    {
      EXPECT_TRUE(segment.castsShadows);
      casterMin = std::min({ casterMin, segment.a.x, segment.b.x });
      casterMax = std::max({ casterMax, segment.a.x, segment.b.x });
    }
    else
    {
      EXPECT_FALSE(segment.castsShadows);
      ++groundSegments;
    }
  }
  EXPECT_NEAR(casterMin, -reach, 1e-6); // float vertices
  EXPECT_NEAR(casterMax, reach, 1e-6);
  EXPECT_GE(groundSegments, 1u);
  // The light's half chord along `across` (a 1 x 1 square).
  EXPECT_NEAR(lightHalfExtentInSection(light, section), 0.5 / std::max(std::abs(horizontal.x), std::abs(horizontal.z)), 1e-12);

  // The shadow map's stored depths drawn along the section: over the caster at its height, elsewhere the ground's.
  const std::vector<SectionTexelColumn> columns = sectionShadowMapColumns(
    *s.frame.lightView, s.frame.lightSpace.front().image, section, s.receiver);
  ASSERT_GT(columns.size(), 10u);
  std::size_t casterColumns = 0;
  for (const SectionTexelColumn& column : columns)
  {
    const bool onCaster = std::abs(column.storedDepth - (kLightHeight - kCasterHeight)) < 1e-4;
    const double expectedY = (onCaster ? kCasterHeight : 0.0) - kLightHeight;
    EXPECT_NEAR(column.enter.y, expectedY, 1e-5) << column.texel.x << "," << column.texel.y;
    EXPECT_NEAR(column.exit.y, expectedY, 1e-5) << column.texel.x << "," << column.texel.y;
    if (onCaster)
    {
      ++casterColumns;
      // The texel's centre ray hit the caster; where the section crosses the texel is within a texel of it.
      const double texelSize = s.frame.lightView->texelWorldSize(column.storedDepth);
      EXPECT_LE(std::abs(0.5 * (column.enter.x + column.exit.x)), reach + texelSize);
    }
  }
  EXPECT_GT(casterColumns, 3u);
}

RgbColor rgbOf(const ImageU8& image, int x, int y)
{
  return { image.at(x, y, 0) / 255.0, image.at(x, y, 1) / 255.0, image.at(x, y, 2) / 255.0 };
}

bool probeFigureHasColor(const ImageU8& image, int x, int y, const RgbColor& color)
{
  const auto rgb = toRgb8(color);
  return image.at(x, y, 0) == rgb[0] && image.at(x, y, 1) == rgb[1] && image.at(x, y, 2) == rgb[2];
}

bool isMarker(const ImageU8& image, int x, int y)
{
  const auto marker = toRgb8(kProbeMarkerColor);
  return image.at(x, y, 0) == marker[0] && image.at(x, y, 1) == marker[1] && image.at(x, y, 2) == marker[2];
}

TEST(ProbeFigure, LaysOutItsPanelsOnTheGridAndMarksThePixel)
{
  for (const glm::ivec2 pixel : { glm::ivec2(20, 30), glm::ivec2(45, 10) })
  {
    SCOPED_TRACE(format("pixel ", pixel.x, ",", pixel.y));
    const Synthetic s = makeSynthetic(pixel);
    const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
    const ImageU8& figure = drawing.image;
    ASSERT_EQ(figure.width, kProbeFigureWidth);
    ASSERT_EQ(figure.height, drawing.layout.height);
    ASSERT_EQ(figure.height % kProbeFigurePanelSide, 0);
    ASSERT_EQ(figure.components, 3);
    // For a look at the figure: build/test-output/probe_figure_<x>_<y>.png.
    std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
    writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / format("probe_figure_", pixel.x, "_", pixel.y, ".png"), figure);
    EXPECT_EQ(kProbeFigureWidth, 1200);
    // The synthetic record has a map, light polygons and samples: image, map, light plane, section, key numbers,
    // lettered in order; no two panels overlap and all lie on the figure.
    for (const ProbePanel panel : { ProbePanel::Image, ProbePanel::ShadowMap, ProbePanel::LightPlane, ProbePanel::Section,
           ProbePanel::Legend })
    {
      EXPECT_TRUE(drawing.layout.rect(panel).has_value()) << int(panel);
    }
    EXPECT_FALSE(drawing.layout.rect(ProbePanel::Penumbra).has_value());
    EXPECT_FALSE(drawing.layout.rect(ProbePanel::Chebyshev).has_value());
    EXPECT_EQ(drawing.layout.letter(ProbePanel::Image), 'a');
    EXPECT_EQ(drawing.layout.letter(ProbePanel::ShadowMap), 'b');
    EXPECT_EQ(drawing.layout.letter(ProbePanel::LightPlane), 'c');
    EXPECT_EQ(drawing.layout.letter(ProbePanel::Section), 'd');
    for (std::size_t i = 0; i < drawing.layout.panels.size(); ++i)
    {
      const FigureRect& a = drawing.layout.panels[i].rect;
      EXPECT_GE(a.left, 0);
      EXPECT_GE(a.bottom, 0);
      EXPECT_LE(a.left + a.width, figure.width);
      EXPECT_LE(a.bottom + a.height, figure.height);
      for (std::size_t j = i + 1; j < drawing.layout.panels.size(); ++j)
      {
        const FigureRect& b = drawing.layout.panels[j].rect;
        const bool apart = a.left + a.width <= b.left || b.left + b.width <= a.left || a.bottom + a.height <= b.bottom ||
          b.bottom + b.height <= a.bottom;
        EXPECT_TRUE(apart) << "panels " << i << " and " << j << " overlap";
      }
    }

    // Panel (a) shows the image where probeImagePlacement says: image pixels away from the marker keep their
    // colour.
    const FigureRect panel = *drawing.layout.rect(ProbePanel::Image);
    const ImagePlacement placement = probeImagePlacement(panel, { 64, 48 });
    EXPECT_GE(placement.scale, 5.0);
    for (const glm::ivec2 imagePixel : { glm::ivec2(2, 2), glm::ivec2(61, 45), glm::ivec2(5, 40) })
    {
      const glm::dvec2 at = placement.figureOf(glm::dvec2(imagePixel) + 0.5);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(figure.at(int(at.x), int(at.y), c), s.frame.image.at(imagePixel.x, imagePixel.y, c))
          << "image pixel " << imagePixel.x << "," << imagePixel.y;
      }
    }
    // The marker: magenta pixels inside panel (a), centred on the pixel's centre.
    glm::dvec2 sum(0.0);
    double count = 0.0;
    for (int y = panel.bottom; y < panel.bottom + panel.height; ++y)
    {
      for (int x = panel.left; x < panel.left + panel.width; ++x)
      {
        if (isMarker(figure, x, y))
        {
          sum += glm::dvec2(x + 0.5, y + 0.5);
          count += 1.0;
        }
      }
    }
    ASSERT_GT(count, 20.0);
    const glm::dvec2 expected = placement.figureOf(glm::dvec2(pixel) + 0.5);
    const glm::dvec2 centroid = sum / count;
    EXPECT_NEAR(centroid.x, expected.x, 1.0);
    EXPECT_NEAR(centroid.y, expected.y, 1.0);
    // The marker surrounds the pixel: it leaves the pixel's own colour visible at its centre.
    const RgbColor inside = rgbOf(figure, int(expected.x), int(expected.y));
    const auto pixelColor = s.frame.image;
    EXPECT_EQ(toRgb8(inside)[0], pixelColor.at(pixel.x, pixel.y, 0));
    EXPECT_EQ(toRgb8(inside)[1], pixelColor.at(pixel.x, pixel.y, 1));
  }
}

// Every text the figure drew lies inside its canvas, and no drawn text is a cut one ("...").
void expectNoProbeFigureTextCut(const ProbeFigureDrawing& drawing)
{
  ASSERT_FALSE(drawing.texts.empty());
  for (const ProbeFigureText& text : drawing.texts)
  {
    EXPECT_TRUE(text.inside) << "panel " << int(text.panel) << ": '" << text.text << "' runs off its canvas";
    EXPECT_EQ(text.text.find("..."), std::string::npos) << text.text;
  }
}

// The legend pages' rows joined back into the lines they wrap (a continuation row starts with two spaces).
std::string probeFigureLegendText(const ProbeFigureDrawing& drawing)
{
  std::string joined;
  for (const ProbeFigureText& text : drawing.texts)
  {
    if (text.panel == ProbePanel::Legend && text.text.rfind("(", 0) != 0) // not a title
    {
      joined += (text.text.rfind("  ", 0) == 0 ? " " + text.text.substr(2) : "\n" + text.text);
    }
  }
  return joined + "\n";
}

TEST(ProbeFigure, DrawsEveryRecordedQuantityInFullOverAsManyPagesAsItTakes)
{
  Synthetic s = makeSynthetic();
  // Sixty steps of long names and a categorical value far wider than a page, then sixty sub-kernel groups that
  // record the same quantities (vssm's record's shape), which the key numbers list as a table.
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const std::string longClass = "non-planar: the mean lies in front of the comparison depth, so Chebyshev's bound "
                                "does not apply and the sub-kernel is split or filtered with PCF";
  for (int k = 0; k < 60; ++k)
  {
    recorder.beginGroup(format("step ", k % 2 == 0 ? "one" : "two", " of many, number ", k, "a"));
    recorder.quantity(format("mean_depth_of_step_", k), 2.5 + 0.001 * k, "linear depth", "test");
    recorder.category("class", k % 2 == 0 ? "planar" : longClass, "test");
  }
  for (int k = 0; k < 60; ++k)
  {
    recorder.beginGroup(format("blocker sub-kernel ", k));
    recorder.quantity("texel_lo", glm::dvec2(100 + k, 200 + k), "texels", "test");
    recorder.quantity("mean_depth", 3.5 + 0.001 * k, "linear depth", "test");
    recorder.category("class", k % 2 == 0 ? "planar" : longClass, "test");
  }
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
  writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / "probe_figure_many_quantities.png", drawing.image);
  expectNoProbeFigureTextCut(drawing);
  EXPECT_GT(drawing.layout.pages(ProbePanel::Legend), 3);
  const std::string legend = probeFigureLegendText(drawing);
  std::size_t checked = 0;
  for (const ProbeQuantity& quantity : s.probe.record.quantities)
  {
    if (quantity.group == "receiver")
    {
      continue; // shown in the summary's own words
    }
    if (quantity.group.rfind("blocker sub-kernel ", 0) == 0)
    {
      // A table row: "<k>: (100+k, 200+k) | 3.5xx | class", every value in full on the group's own line.
      const std::string index = quantity.group.substr(std::string("blocker sub-kernel ").size());
      const std::size_t row = legend.find("\n" + index + ": ");
      ASSERT_NE(row, std::string::npos) << quantity.group;
      const std::string rowText = legend.substr(row + 1, legend.find('\n', row + 1) - row - 1);
      const std::string value = quantity.text.empty()
        ? (quantity.value.size() == 1 ? readableNumber(quantity.value[0], 4)
                                      : "(" + readableNumber(quantity.value[0], 4) + ", " + readableNumber(quantity.value[1], 4) + ")")
        : quantity.text;
      EXPECT_NE(rowText.find(value), std::string::npos) << quantity.group << " " << quantity.name << ": " << rowText;
      ++checked;
      continue;
    }
    const std::string line = probeQuantityText(quantity);
    EXPECT_NE(std::find(drawing.legendLines.begin(), drawing.legendLines.end(), line), drawing.legendLines.end()) << line;
    EXPECT_NE(legend.find("\n" + line + "\n"), std::string::npos) << "not drawn in full: " << line;
    ++checked;
  }
  EXPECT_EQ(checked, 300u);
  // The table's heading names its columns with their units.
  EXPECT_NE(legend.find("-- blocker sub-kernel (60 groups, one line each): texel_lo [texels] | mean_depth [linear "
                        "depth] | class --"),
    std::string::npos);
  // Every legend line, the last page's included, is on the figure.
  for (const std::string& line : drawing.legendLines)
  {
    EXPECT_NE(legend.find("\n" + line + "\n"), std::string::npos) << line;
  }
}

// The fraction of a panel's content (below the title band) that is not white.
double probeFigureInkFraction(const ImageU8& figure, const FigureRect& rect)
{
  std::size_t ink = 0;
  std::size_t total = 0;
  for (int y = rect.bottom + 4; y < rect.bottom + rect.height - 30; ++y)
  {
    for (int x = rect.left + 4; x < rect.left + rect.width - 4; ++x)
    {
      ++total;
      ink += (figure.at(x, y, 0) < 250 || figure.at(x, y, 1) < 250 || figure.at(x, y, 2) < 250) ? 1 : 0;
    }
  }
  return double(ink) / double(total);
}

TEST(ProbeFigure, LeavesOutPanelsWithoutContentAndInksEveryOther)
{
  Synthetic s = makeSynthetic();
  // Nothing on the light (hard, pcf, pcss, vsm): no light-plane panel.
  s.probe.record.lightPolygons.clear();
  s.probe.record.lightSamples.clear();
  s.probe.record.contourEdges.clear();
  ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  EXPECT_FALSE(drawing.layout.rect(ProbePanel::LightPlane).has_value());
  // Letters run on without a gap: a, b, c, ... in layout order.
  for (std::size_t i = 0; i < drawing.layout.panels.size(); ++i)
  {
    EXPECT_EQ(drawing.layout.panels[i].letter, char('a' + i));
  }
  for (const ProbeFigurePanel& panel : drawing.layout.panels)
  {
    EXPECT_GT(probeFigureInkFraction(drawing.image, panel.rect), 0.01) << "panel (" << panel.letter << ") is empty";
  }
  // No shadow map (dcs, shadow volumes): no map panel.
  s.frame.lightSpace.clear();
  s.frame.lightView.reset();
  s.probe.record.lightSamples.push_back({ { 0.1, 0.1 }, true, 1 });
  drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  EXPECT_FALSE(drawing.layout.rect(ProbePanel::ShadowMap).has_value());
  EXPECT_TRUE(drawing.layout.rect(ProbePanel::LightPlane).has_value());
  for (const ProbeFigurePanel& panel : drawing.layout.panels)
  {
    EXPECT_GT(probeFigureInkFraction(drawing.image, panel.rect), 0.01) << "panel (" << panel.letter << ") is empty";
  }
  expectNoProbeFigureTextCut(drawing);
}

// Which texts of a panel contain `part`.
bool probeFigurePanelSays(const ProbeFigureDrawing& drawing, ProbePanel panel, const std::string& part)
{
  return std::any_of(drawing.texts.begin(), drawing.texts.end(),
    [&](const ProbeFigureText& text) { return text.panel == panel && text.text.find(part) != std::string::npos; });
}

std::string probeFigurePanelText(const ProbeFigureDrawing& drawing, ProbePanel panel)
{
  std::string joined;
  for (const ProbeFigureText& text : drawing.texts)
  {
    joined += text.panel == panel ? text.text + " | " : "";
  }
  return joined;
}

TEST(ProbeFigure, PcssPanelDrawsTheSimilarTrianglesWithThePixelsNumbers)
{
  Synthetic s = makeSynthetic();
  s.probe.record.lightPolygons.clear();
  s.probe.record.lightSamples.clear();
  s.probe.record.contourEdges.clear();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const double lightSize = 1.2;
  const double nearDepth = 1.7;
  const double blockerDepth = 2.546;
  const double receiverDepth = s.probe.record.find("receiver_depth")->value[0];
  recorder.beginGroup("blocker search");
  recorder.quantity("light_size", lightSize, "world units", "test");
  recorder.quantity("search_plane_depth", nearDepth, "linear depth", "test");
  recorder.beginGroup("penumbra estimate");
  recorder.quantity("avg_blocker_depth", blockerDepth, "linear depth", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
  writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / "probe_figure_pcss.png", drawing.image);
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Penumbra).has_value());
  EXPECT_FALSE(drawing.layout.rect(ProbePanel::Chebyshev).has_value());
  // Fernando 2005: w_penumbra = w_light (d_r - d_b) / d_b; the search region w_light (d_r - n) / d_r.
  const std::string penumbra = readableNumber(lightSize * (receiverDepth - blockerDepth) / blockerDepth, 4);
  const std::string search = readableNumber(lightSize * (receiverDepth - nearDepth) / receiverDepth, 4);
  const std::string text = probeFigurePanelText(drawing, ProbePanel::Penumbra);
  EXPECT_NE(text.find("= " + penumbra + " world units"), std::string::npos) << text;
  EXPECT_NE(text.find("= " + search + " world units"), std::string::npos) << text;
  EXPECT_TRUE(probeFigurePanelSays(drawing, ProbePanel::Penumbra, "d_b 2.55")) << text;
  // The light drawn in gold, the penumbra span in blue on the receiver line.
  const FigureRect rect = *drawing.layout.rect(ProbePanel::Penumbra);
  std::size_t gold = 0;
  for (int y = rect.bottom; y < rect.bottom + rect.height; ++y)
  {
    for (int x = rect.left; x < rect.left + rect.width; ++x)
    {
      gold += probeFigureHasColor(drawing.image, x, y, { 1.0, 0.85, 0.2 }) ? 1 : 0;
    }
  }
  EXPECT_GT(gold, 50u);
  expectNoProbeFigureTextCut(drawing);
}

TEST(ProbeFigure, MomentPanelDrawsTheChebyshevBoundAtThePixel)
{
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const double mean = 3.1;
  const double variance = 0.004;
  const double t = 3.19;
  recorder.beginGroup("moments");
  recorder.quantity("mean", mean, "linear depth", "test");
  recorder.quantity("variance", variance, "linear depth^2", "test");
  recorder.beginGroup("chebyshev");
  recorder.quantity("compared_depth", t, "linear depth", "test");
  recorder.quantity("p_max", variance / (variance + (t - mean) * (t - mean)), "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
  writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / "probe_figure_chebyshev.png", drawing.image);
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Chebyshev).has_value());
  EXPECT_FALSE(drawing.layout.rect(ProbePanel::Penumbra).has_value());
  const std::string bound = readableNumber(variance / (variance + (t - mean) * (t - mean)), 4);
  const std::string text = probeFigurePanelText(drawing, ProbePanel::Chebyshev);
  EXPECT_NE(text.find("= " + bound), std::string::npos) << text;
  EXPECT_NE(text.find("mean 3.1"), std::string::npos) << text;
  EXPECT_NE(text.find("t 3.19"), std::string::npos) << text;
  expectNoProbeFigureTextCut(drawing);
}

TEST(ProbeFigure, EsmPanelDrawsTheFilteredExponentialAtThePixel)
{
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const double c = 40.0;
  const double moment = std::exp(c * 0.6) * 0.5; // half the region at z_n = 0.6, the other half far (exp -> 0)
  const double t = 0.62;
  recorder.beginGroup("moments");
  recorder.quantity("esm_exponent", c, "", "test");
  recorder.quantity("exponential_moment", moment, "", "test");
  recorder.beginGroup("exponential test");
  recorder.quantity("normalized_compared_depth", t, "", "test");
  recorder.quantity("visibility", std::min(1.0, moment * std::exp(-c * t)), "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
  writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / "probe_figure_esm.png", drawing.image);
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Exponential).has_value());
  const std::string text = probeFigurePanelText(drawing, ProbePanel::Exponential);
  // Annen et al. 2008: E[exp(c z)] exp(-c t) = 0.5 exp(40 (0.6 - 0.62)) = 0.2247; the fall from 1 at
  // ln(E) / c = 0.6 - ln 2 / 40.
  EXPECT_NE(text.find("= " + readableNumber(0.5 * std::exp(c * (0.6 - t)), 4) + " (recorded"), std::string::npos) << text;
  EXPECT_NE(text.find("= " + readableNumber(0.6 - std::log(2.0) / c, 4)), std::string::npos) << text;
  expectNoProbeFigureTextCut(drawing);
}

TEST(ProbeFigure, MomentPanelIsLeftOutWhenTheMomentsAndTheComparedDepthAreInDifferentSpaces)
{
  // lvsm's shape: moments in warped depth, compared_depth linear; a bound drawn from them would not be the one the
  // technique took.
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  recorder.beginGroup("moments");
  recorder.quantity("mean", 0.0, "warped depth", "test");
  recorder.quantity("variance", 1e-4, "warped depth^2", "test");
  recorder.beginGroup("chebyshev");
  recorder.quantity("compared_depth", 3.2, "linear depth", "test");
  recorder.quantity("p_max", 4.5e-6, "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  EXPECT_FALSE(drawing.layout.rect(ProbePanel::Chebyshev).has_value());
  // The quantities are still all in the key numbers.
  EXPECT_NE(std::find(drawing.legendLines.begin(), drawing.legendLines.end(), "mean 0 warped depth"),
    drawing.legendLines.end());
}

// A panel's texts joined as prose: its wrapped lines rejoined at the spaces they broke at.
std::string probeFigurePanelProse(const ProbeFigureDrawing& drawing, ProbePanel panel)
{
  std::string joined;
  for (const ProbeFigureText& text : drawing.texts)
  {
    joined += text.panel == panel ? text.text + " " : "";
  }
  return joined;
}

// Writes the figure under the test output directory (to look at) and checks that no text of it was cut.
void writeAndCheckProbeFigure(const ProbeFigureDrawing& drawing, const std::string& name)
{
  std::filesystem::create_directories(SL_TEST_OUTPUT_DIR);
  writePng(std::filesystem::path(SL_TEST_OUTPUT_DIR) / ("probe_figure_" + name + ".png"), drawing.image);
  expectNoProbeFigureTextCut(drawing);
}

TEST(ProbeFigure, ComparisonPanelDrawsEachPcfTapLitOrShadowed)
{
  // The synthetic record's 3 x 3 taps, weight 1/9 each, 5 in front of the receiver (a checkerboard): pcf's
  // visibility is the lit share 4/9 (Reeves et al. 1987 §3).
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  recorder.beginGroup("result");
  recorder.quantity("lit_taps", 4.0 / 9.0, "count", "test");
  recorder.quantity("visibility", 4.0 / 9.0, "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "pcf_comparisons");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Comparisons).has_value());
  ASSERT_TRUE(drawing.drawnValue(ProbePanel::Comparisons, "lit_fraction").has_value());
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::Comparisons, "lit_fraction"), 4.0 / 9.0, 1e-12);
  EXPECT_EQ(*drawing.drawnValue(ProbePanel::Comparisons, "texels"), double(s.comparedTexels.size()));
  const std::string text = probeFigurePanelProse(drawing, ProbePanel::Comparisons);
  EXPECT_NE(text.find("4 lit (white), 5 shadowed (black)"), std::string::npos) << text;
  // Each cell in its colour: the shadowed ones dark (the caster colour), the lit ones white, about 5 : 4.
  const FigureRect rect = *drawing.layout.rect(ProbePanel::Comparisons);
  std::size_t dark = 0;
  for (int y = rect.bottom; y < rect.bottom + rect.height; ++y)
  {
    for (int x = rect.left; x < rect.left + rect.width; ++x)
    {
      dark += probeFigureHasColor(drawing.image, x, y, { 0.12, 0.12, 0.12 }) ? 1 : 0;
    }
  }
  EXPECT_GT(dark, std::size_t(rect.width * rect.height) / 10) << "the 5 shadowed cells are not drawn";
  // Without lit_taps (a technique whose compared texels serve another diagram) the panel is left out.
  s = makeSynthetic();
  EXPECT_FALSE(drawProbeFigure(s.probe, s.frame, s.scene).layout.rect(ProbePanel::Comparisons).has_value());
}

TEST(ProbeFigure, LayersPanelFindsTheRecordedLayerFromTheEnds)
{
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const std::vector<double> ends = { 1.0, 2.0, 2.5, 4.0, 6.0 };
  const double t = 3.1; // layer 2, phi = (3.1 - 2.5) / 1.5 = 0.4
  recorder.beginGroup("layer");
  recorder.quantity("layer", 2.0, "", "test");
  for (std::size_t i = 0; i < ends.size(); ++i)
  {
    recorder.quantity(format("layer_end_", i), ends[i], "linear depth", "test");
  }
  recorder.quantity("compared_depth", t, "linear depth", "test");
  recorder.quantity("warped_depth", 0.4, "", "test");
  recorder.beginGroup("moments");
  recorder.quantity("mean", 0.3, "warped depth", "test");
  recorder.quantity("variance", 0.001, "warped depth^2", "test");
  recorder.beginGroup("chebyshev");
  recorder.quantity("own_layer_p_max", 0.0909, "", "test");
  for (int j = 0; j < 4; ++j)
  {
    recorder.quantity(format("layer", j, "_p_max"), 0.2 * (j + 1), "", "test");
  }
  recorder.quantity("bound_source", 0.0, "layer", "test");
  recorder.quantity("p_max", 0.2, "", "test");
  s.probe.record = recorder.record();
  ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "lvsm_layers");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Layers).has_value());
  EXPECT_EQ(drawing.drawnValue(ProbePanel::Layers, "layer"), 2.0);
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::Layers, "warped_depth"), 0.4, 1e-12);
  const std::string text = probeFigurePanelProse(drawing, ProbePanel::Layers);
  EXPECT_NE(text.find("in layer 2 [p, q] = [2.5, 4]"), std::string::npos) << text;
  EXPECT_NE(text.find("(from layer 0)"), std::string::npos) << text;
  // A depth on a boundary belongs to the farther layer (LayeredMoments.h), one past the far end to the last.
  for (const auto& [depth, layer] : { std::pair<double, double>{ 2.0, 1.0 }, { 7.0, 3.0 }, { 0.5, 0.0 } })
  {
    s.probe.record.quantities.erase(std::remove_if(s.probe.record.quantities.begin(), s.probe.record.quantities.end(),
                                      [](const ProbeQuantity& q) { return q.name == "compared_depth"; }),
      s.probe.record.quantities.end());
    s.probe.record.quantities.push_back({ "layer", "compared_depth", { depth }, "linear depth", "test", "" });
    drawing = drawProbeFigure(s.probe, s.frame, s.scene);
    EXPECT_EQ(drawing.drawnValue(ProbePanel::Layers, "layer"), layer) << "t = " << depth;
  }
}

TEST(ProbeFigure, MomentBoundPanelTakesTheWeightInFrontOfTheReceiver)
{
  // A three-point distribution: z_2 = 0.3 (w 0.25) in front of z_f = 0.5 (w 0.6), z_3 = 0.8 (w 0.15) behind:
  // MSM Alg. 3's shadow intensity is the weight in front, 0.25.
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  recorder.beginGroup("moments");
  recorder.quantity("power_moments", glm::dvec3(0.47, 0.2665, 0.1593), "", "test");
  recorder.quantity("power_moment_4", 0.0996, "", "test");
  recorder.beginGroup("hamburger 4msm");
  recorder.quantity("fragment_depth", 0.5, "moment depth", "test");
  recorder.quantity("support_depth_near", 0.3, "moment depth", "test");
  recorder.quantity("support_depth_far", 0.8, "moment depth", "test");
  recorder.quantity("support_weights", glm::dvec3(0.6, 0.25, 0.15), "", "test");
  recorder.quantity("shadow_intensity", 0.25, "", "test");
  s.probe.record = recorder.record();
  ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "msm_moment_bound");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::MomentBound).has_value());
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::MomentBound, "shadow_intensity"), 0.25, 1e-12);
  const std::string text = probeFigurePanelProse(drawing, ProbePanel::MomentBound);
  EXPECT_NE(text.find("z_2 0.3"), std::string::npos) << text;
  EXPECT_NE(text.find("(recorded 0.25)"), std::string::npos) << text;
  // The receiver behind both: both weights in front, 0.4.
  for (ProbeQuantity& quantity : s.probe.record.quantities)
  {
    if (quantity.name == "fragment_depth")
    {
      quantity.value = { 0.9 };
    }
  }
  drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::MomentBound, "shadow_intensity"), 0.4, 1e-12);
}

TEST(ProbeFigure, FourierPanelDrawsTheFilteredSeriesAndTheStepsRinging)
{
  // One term (M = 1, sigma 1) and nine recorded samples of a filtered f: the panel's f(d_s) is the sample at d_s, and
  // its overshoot the samples' largest excursion outside [0, 1].
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  const double ds = 0.4;
  recorder.beginGroup("fourier");
  recorder.quantity("terms", 1.0, "", "test");
  recorder.quantity("d_series", ds, "", "test");
  recorder.quantity("c_1", test::kPi, "", "test");
  recorder.quantity("sigma_1", 1.0, "", "test");
  const auto filtered = [&](double d) { return 0.5 + 2.0 / test::kPi * 0.8 * std::sin(test::kPi * (0.45 - d)); };
  for (int j = -4; j <= 4; ++j)
  {
    const double d = ds + j / 2.0;
    recorder.quantity(format("reconstructed_step_", j + 4), glm::dvec2(d, filtered(d)), "", "test");
  }
  recorder.quantity("reconstruction", filtered(ds), "", "test");
  recorder.quantity("reconstruction_scale", 2.0, "", "test");
  recorder.quantity("visibility", std::clamp(2.0 * filtered(ds), 0.0, 1.0), "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "convsm_fourier");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::Fourier).has_value());
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::Fourier, "reconstruction"), filtered(ds), 1e-12);
  double overshoot = 0.0;
  for (int j = -4; j <= 4; ++j)
  {
    const double value = filtered(ds + j / 2.0);
    overshoot = std::max({ overshoot, value - 1.0, -value });
  }
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::Fourier, "overshoot"), overshoot, 1e-12);
  const std::string text = probeFigurePanelProse(drawing, ProbePanel::Fourier);
  EXPECT_NE(text.find("M = 1"), std::string::npos) << text;
  // The grey curve, one occluder at d_s in the one-term series 1/2 + (2 / pi) sin(pi (d_s - d')): its overshoot
  // past 1 is 2 / pi - 1/2 where the sine peaks inside the drawn depths [d_s - 2, d_s + 2].
  // (drawn from 301 samples of the curve: within 1e-3).
  ASSERT_TRUE(drawing.drawnValue(ProbePanel::Fourier, "step_overshoot").has_value());
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::Fourier, "step_overshoot"), 2.0 / test::kPi - 0.5, 1e-3);
}

TEST(ProbeFigure, LevelBlendPanelBlendsTheTwoLevelsVisibilities)
{
  // SS08 §4.2: l = 2.3 blends level 2 (weight 0.7, V 0.5) and level 3 (weight 0.3, V 0.8): V = 0.59.
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  recorder.beginGroup("blend");
  recorder.quantity("loq", 2.3, "levels", "test");
  recorder.quantity("level_ceil", 3.0, "level", "test");
  recorder.quantity("blend_band", 1.0, "levels", "test");
  recorder.quantity("weight_floor", 0.7, "", "test");
  recorder.quantity("weight_ceil", 0.3, "", "test");
  recorder.beginGroup("level 2 (floor)");
  recorder.quantity("level_visibility", 0.5, "", "test");
  recorder.beginGroup("level 3 (ceil)");
  recorder.quantity("level_visibility", 0.8, "", "test");
  recorder.beginGroup("result");
  recorder.quantity("visibility", 0.59, "", "test");
  s.probe.record = recorder.record();
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "ss08_level_blend");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::LevelBlend).has_value());
  EXPECT_NEAR(*drawing.drawnValue(ProbePanel::LevelBlend, "visibility"), 0.7 * 0.5 + 0.3 * 0.8, 1e-12);
  const std::string text = probeFigurePanelProse(drawing, ProbePanel::LevelBlend);
  EXPECT_NE(text.find("level 2 weight 0.7 V 0.5, level 3 weight 0.3 V 0.8"), std::string::npos) << text;
  EXPECT_NE(text.find("= 0.59 (recorded 0.59)"), std::string::npos) << text;
  // Without the levels' visibilities (a pixel decided before any back-projection) the panel is left out.
  s = makeSynthetic();
  EXPECT_FALSE(drawProbeFigure(s.probe, s.frame, s.scene).layout.rect(ProbePanel::LevelBlend).has_value());
}

TEST(ProbeFigure, IrregularTexelPanelIsLitUnlessATestedTriangleCovers)
{
  Synthetic s = makeSynthetic();
  ProbeRecorder recorder;
  recorder.record() = s.probe.record;
  recorder.beginGroup("light-space grid");
  recorder.quantity("face", 3.0, "", "test");
  recorder.quantity("texel", glm::dvec2(131.52, 187.54), "texels", "test");
  recorder.beginGroup("triangles over the texel");
  recorder.quantity("triangle_7 (within rounding)", glm::dvec3(0.0), "world units (first vertex)", "test");
  recorder.quantity("izb_triangle_tests", 2.0, "triangles", "test");
  recorder.quantity("gpu_izb_triangle_tests", 2.0, "triangles", "test");
  recorder.quantity("gpu_izb_list_length", 3.0, "samples", "test");
  recorder.beginGroup("result");
  recorder.quantity("visibility", 1.0, "", "test");
  const ProbeRecord withinRounding = recorder.record();
  s.probe.record = withinRounding;
  ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  writeAndCheckProbeFigure(drawing, "izb_texel");
  ASSERT_TRUE(drawing.layout.rect(ProbePanel::IrregularTexel).has_value());
  // A triangle within rounding makes the pixel ambiguous, it does not cover: lit.
  EXPECT_EQ(drawing.drawnValue(ProbePanel::IrregularTexel, "visibility"), 1.0);
  EXPECT_EQ(drawing.drawnValue(ProbePanel::IrregularTexel, "covering_triangles"), 0.0);
  std::string text = probeFigurePanelProse(drawing, ProbePanel::IrregularTexel);
  EXPECT_NE(text.find("texel (131, 187)"), std::string::npos) << text;
  EXPECT_NE(text.find("its list: 3 samples"), std::string::npos) << text;
  // One that covers: shadowed.
  recorder.beginGroup("triangles over the texel");
  recorder.quantity("triangle_12 (covers)", glm::dvec3(0.0), "world units (first vertex)", "test");
  s.probe.record = recorder.record();
  drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  EXPECT_EQ(drawing.drawnValue(ProbePanel::IrregularTexel, "visibility"), 0.0);
  EXPECT_EQ(drawing.drawnValue(ProbePanel::IrregularTexel, "covering_triangles"), 1.0);
  text = probeFigurePanelProse(drawing, ProbePanel::IrregularTexel);
  EXPECT_NE(text.find("between it and the light: triangle_12"), std::string::npos) << text;
}

TEST(ProbeFigure, ColourBarTicksDifferOverANarrowRange)
{
  Synthetic s = makeSynthetic();
  // A map whose crop holds depths 3.46 .. 3.48 only: three significant digits would repeat labels.
  ImageF& depth = s.frame.lightSpace.front().image;
  for (int y = 0; y < depth.height; ++y)
  {
    for (int x = 0; x < depth.width; ++x)
    {
      depth.at(x, y) = float(3.46 + 0.02 * (x + y) / double(depth.width + depth.height));
    }
  }
  const ProbeFigureDrawing drawing = drawProbeFigure(s.probe, s.frame, s.scene);
  ASSERT_FALSE(drawing.colorBarTicks.empty());
  for (const std::vector<std::string>& ticks : drawing.colorBarTicks)
  {
    ASSERT_EQ(ticks.size(), 5u);
    const std::set<std::string> distinct(ticks.begin(), ticks.end());
    std::string all;
    for (const std::string& tick : ticks)
    {
      all += tick + " ";
    }
    EXPECT_EQ(distinct.size(), ticks.size()) << all;
  }
}

TEST(NumberText, RoundsForPeopleAndTicksDiffer)
{
  EXPECT_EQ(readableNumber(1.171875), "1.17");
  EXPECT_EQ(readableNumber(2.0), "2");
  EXPECT_EQ(readableNumber(0.000123456), "0.000123");
  EXPECT_EQ(readableNumber(1234.4), "1234");
  EXPECT_EQ(readableNumber(-0.0), "0");
  EXPECT_EQ(readableNumber(2.5e-7), "2.5e-07");
  EXPECT_EQ(readableNumber(std::numeric_limits<double>::quiet_NaN()), "n/a");
  const std::vector<std::string> ticks = distinctTickLabels({ 3.4752, 3.4731, 3.4710, 3.4689, 3.4668 });
  EXPECT_EQ(ticks, (std::vector<std::string>{ "3.475", "3.473", "3.471", "3.469", "3.467" }));
  EXPECT_EQ(distinctTickLabels({ 0.0, 0.5, 1.0 }), (std::vector<std::string>{ "0", "0.5", "1" }));
}

TEST(NumberText, WrapsAStatusLineToTheWidthKeepingEveryWord)
{
  // The viewer's status (issue 31: it ran off the window): a screenshot line with its render command.
  const std::string line = "screenshot shots/view-003-hard-texel_ratio.png = shadowlab render "
                           "datasets/contact/scene.json -t hard --set bias_constant_texels=2 --scene-set "
                           "/lights/0/size=1 --resolution 128x128";
  for (const std::size_t width : { std::size_t(16), std::size_t(40), std::size_t(80), std::size_t(500) })
  {
    const std::vector<std::string> lines = wrapAtSpaces(line, width);
    std::string joined;
    for (std::size_t i = 0; i < lines.size(); ++i)
    {
      EXPECT_LE(lines[i].size(), width) << "'" << lines[i] << "'";
      if (i > 0)
      {
        ASSERT_EQ(lines[i].rfind("  ", 0), 0u) << lines[i];
      }
      joined += i == 0 ? lines[i] : lines[i].substr(2);
    }
    std::string withoutSpaces = line;
    withoutSpaces.erase(std::remove(withoutSpaces.begin(), withoutSpaces.end(), ' '), withoutSpaces.end());
    joined.erase(std::remove(joined.begin(), joined.end(), ' '), joined.end());
    EXPECT_EQ(joined, withoutSpaces) << "width " << width;
    EXPECT_EQ(lines.size() == 1, line.size() <= width) << "width " << width;
  }
  // Words break at spaces where a line stays at least half full.
  EXPECT_EQ(wrapAtSpaces("aaaa bbbb cccc dddd eeee", 16), (std::vector<std::string>{ "aaaa bbbb cccc", "  dddd eeee" }));
}

TEST(CanvasShapes, FillsAndStrokesWhatTheyCover)
{
  ImageU8 canvas(40, 30, 3, 0);
  fillPolygon(canvas, { { 10, 5 }, { 20, 5 }, { 20, 15 }, { 10, 15 } }, kWhite);
  int filled = 0;
  for (int y = 0; y < canvas.height; ++y)
  {
    for (int x = 0; x < canvas.width; ++x)
    {
      const bool inside = x >= 10 && x < 20 && y >= 5 && y < 15;
      filled += canvas.at(x, y, 0) == 255 ? 1 : 0;
      EXPECT_EQ(canvas.at(x, y, 0), inside ? 255 : 0) << x << "," << y;
    }
  }
  EXPECT_EQ(filled, 100);
  // A thin diagonal line leaves no column empty between its ends, and nothing far from it is painted.
  ImageU8 line(40, 30, 3, 0);
  drawLine(line, { 2.5, 3.5 }, { 37.5, 20.5 }, kWhite, 1.0);
  for (int x = 3; x <= 37; ++x)
  {
    int painted = 0;
    for (int y = 0; y < line.height; ++y)
    {
      if (line.at(x, y, 0) == 255)
      {
        ++painted;
        const double lineY = 3.5 + (x + 0.5 - 2.5) * (17.0 / 35.0);
        EXPECT_LE(std::abs(y + 0.5 - lineY), 1.0) << x << "," << y;
      }
    }
    EXPECT_GE(painted, 1) << "column " << x;
  }
  // Far outside the canvas: nothing, and no endless loop.
  ImageU8 empty(10, 10, 3, 0);
  drawLine(empty, { -1e12, -1e12 }, { -1e12 + 1, 5e11 }, kWhite, 3.0);
  drawDashedLine(empty, { -1e9, 5.0 }, { 1e9, 5.0 }, kWhite, 1.0, 4.0);
  int paintedRow = 0;
  for (int x = 0; x < 10; ++x)
  {
    paintedRow += empty.at(x, 5, 0) == 255 ? 1 : 0;
  }
  EXPECT_GE(paintedRow, 3); // the dashed line crosses the canvas: dashes and gaps 4 px long (plus round caps)
  EXPECT_LE(paintedRow, 8);
}

} // namespace
} // namespace sl
