// `shadowlab probe`'s contract for every registered technique (issue 15): each has a probe recorder, and on two
// datasets and three pixels (lit, penumbra, umbra) the replay's visibility equals the GPU buffer's within the
// tolerance of that technique's GPU-CPU tests, unless the replay reports the pixel ambiguous (a decision within
// float rounding of its boundary, which those tests exclude too). A recorded quantity that carries the name of one
// of the technique's buffers must equal that buffer at the pixel: the record shows what the GPU computed.
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "probe/Probe.h"
#include "probe/ProbeFigure.h"
#include "probe/ProbeGeometry.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <set>

namespace sl
{
namespace
{

TEST(Probe, EveryRegisteredTechniqueHasAProbeRecorder)
{
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    EXPECT_TRUE(static_cast<bool>(technique.probe)) << technique.name << " declares no probe recorder";
  }
}

// Each technique on the first two of these datasets its light supports: stacked occluders (overlapping
// penumbrae, non-planar blockers) and the bunny (a curved, tessellated caster that shadows itself).
std::vector<test::DatasetTechnique> probeCases()
{
  const std::vector<std::string> preferred = { "stacked-occluders", "bunny", "planar-occluder", "contact", "sphere-point" };
  std::vector<test::DatasetTechnique> cases;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    int taken = 0;
    for (const std::string& dataset : preferred)
    {
      const std::vector<std::string> rendered = test::datasetsRenderedBy(technique.name);
      if (taken < 2 && std::find(rendered.begin(), rendered.end(), dataset) != rendered.end())
      {
        cases.push_back({ dataset, technique.name });
        ++taken;
      }
    }
  }
  return cases;
}

enum class PixelKind
{
  Lit,
  Penumbra,
  Umbra
};

const char* kindName(PixelKind kind)
{
  return kind == PixelKind::Lit ? "lit" : kind == PixelKind::Penumbra ? "penumbra" : "umbra";
}

// Whether the technique's categorical buffers mark the pixel cut short (not exact on the GPU: nothing to compare).
bool cutShortAt(const FrameResult& frame, int x, int y)
{
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    const NamedImage* named = spec.cutShortCode >= 0 ? frame.find(spec.name) : nullptr;
    if (named != nullptr && std::lround(named->image.at(x, y)) == spec.cutShortCode)
    {
      return true;
    }
  }
  return false;
}

// The receiving pixels of a kind, in scan order. Penumbra: 0.02 < V < 0.98; for a technique without partial values
// (hard shadows) a lit pixel beside an umbra pixel, where the shadow's edge is.
// Umbra: only receivers facing the light (cosine > 0.2), so that V = 0 comes from a shadow test, not from facing away.
std::vector<glm::ivec2> pixelsOfKind(const FrameResult& frame, const Light& light, PixelKind kind)
{
  const ImageF& position = frame.find("position")->image;
  const ImageF& normal = frame.find("normal")->image;
  const auto facesLight = [&](int x, int y) {
    const glm::dvec3 p(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
    const glm::dvec3 n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
    return glm::dot(n, directionToLight(light, p)) > 0.2;
  };
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const auto receiving = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < visibility.width && y < visibility.height && coverage.at(x, y) > 0.5f &&
      receives.at(x, y) > 0.5f && !cutShortAt(frame, x, y);
  };
  std::vector<glm::ivec2> partial;
  std::vector<glm::ivec2> edge;
  std::vector<glm::ivec2> chosen;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      if (!receiving(x, y))
      {
        continue;
      }
      const float v = visibility.at(x, y);
      if (kind == PixelKind::Lit && v == 1.0f)
      {
        chosen.emplace_back(x, y);
      }
      else if (kind == PixelKind::Umbra && v == 0.0f && facesLight(x, y))
      {
        chosen.emplace_back(x, y);
      }
      else if (kind == PixelKind::Penumbra)
      {
        if (v > 0.02f && v < 0.98f)
        {
          partial.emplace_back(x, y);
        }
        else if (v == 1.0f)
        {
          for (const glm::ivec2 step : { glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1) })
          {
            if (receiving(x + step.x, y + step.y) && visibility.at(x + step.x, y + step.y) == 0.0f)
            {
              edge.emplace_back(x, y);
              break;
            }
          }
        }
      }
    }
  }
  if (kind == PixelKind::Penumbra)
  {
    return partial.size() >= 8 ? partial : edge;
  }
  return chosen;
}

class ProbeAgreement : public testing::TestWithParam<test::DatasetTechnique>
{
};

TEST_P(ProbeAgreement, TwinVisibilityEqualsTheGpuBufferOnLitPenumbraAndUmbraPixels)
{
  const test::DatasetTechnique& param = GetParam();
  const Scene scene = test::loadDataset(param.dataset);
  const TechniqueDescriptor& technique = findTechnique(param.technique);
  const FrameResult frame = test::renderDataset(scene, param.technique, 96, 96, technique.sweepTestSettings);
  int agreedUnambiguous = 0;
  for (const PixelKind kind : { PixelKind::Lit, PixelKind::Penumbra, PixelKind::Umbra })
  {
    const std::vector<glm::ivec2> candidates = pixelsOfKind(frame, scene.lights.front(), kind);
    if (candidates.empty())
    {
      // vtk's own pass filters its map: it may have no exact 0 or 1 anywhere; every other technique has all three.
      EXPECT_TRUE(kind != PixelKind::Lit || param.technique == "vtk") << param.dataset << " " << param.technique
                                                                       << ": no " << kindName(kind) << " pixel";
      std::cout << "[ measured ] " << param.dataset << " " << param.technique << ": no " << kindName(kind) << " pixel\n";
      continue;
    }
    // Up to 24 candidates spread over the scan order: the first that reaches a shadow test (an umbra pixel may
    // just face away from the light) with an unambiguous replay is kept, else the last that reached one.
    std::optional<ProbeResult> kept;
    for (int attempt = 0; attempt < 24; ++attempt)
    {
      const std::size_t index = (2 * static_cast<std::size_t>(attempt) + 1) * candidates.size() / 48;
      ProbeResult probe = probePixel(frame, scene, 0, candidates[std::min(index, candidates.size() - 1)]);
      const bool evaluated = probe.outcome.evaluated;
      const bool ambiguous = !probe.outcome.ambiguity.empty();
      if (!kept || evaluated || !kept->outcome.evaluated)
      {
        kept = std::move(probe);
      }
      if (evaluated && !ambiguous)
      {
        break;
      }
    }
    const ProbeResult& probe = *kept;
    const std::string label = format(param.dataset, " ", param.technique, " ", kindName(kind), " pixel ", probe.pixel.x,
      ",", probe.pixel.y);
    std::cout << "[ measured ] " << label << ": GPU " << probe.gpuVisibility << ", twin " << probe.outcome.visibility
              << ", |difference| " << probe.difference() << " (tolerance " << probe.outcome.tolerance << ")"
              << (probe.outcome.ambiguity.empty() ? "" : ", ambiguous: " + probe.outcome.ambiguity) << ", "
              << probe.record.quantities.size() << " quantities, " << probe.record.texels.size() << " texels, "
              << probe.record.nodes.size() << " nodes\n";
    EXPECT_TRUE(probe.agrees()) << label << ": GPU " << probe.gpuVisibility << " twin " << probe.outcome.visibility;
    EXPECT_FALSE(probe.record.quantities.empty()) << label << ": nothing recorded";
    EXPECT_FALSE(probe.outcome.twin.empty()) << label << ": the outcome must say what was replayed";
    EXPECT_TRUE(probe.outcome.evaluated) << label << ": no candidate pixel reached a shadow test";
    if (!probe.outcome.ambiguity.empty())
    {
      continue;
    }
    ++agreedUnambiguous;
    // A "<name>_sensitivity" quantity of the record's conditioning group above 1e-3 (the techniques' limit, e.g.
    // msmSoftSensitivityLimit) says the quantities named "<name>..." are ill-conditioned in float: not compared.
    const auto illConditioned = [&](const std::string& name) {
      return std::any_of(probe.record.quantities.begin(), probe.record.quantities.end(), [&](const ProbeQuantity& other) {
        const std::string suffix = "_sensitivity";
        return other.group == "conditioning" && other.name.size() > suffix.size() &&
          other.name.compare(other.name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          name.rfind(other.name.substr(0, other.name.size() - suffix.size()), 0) == 0 && other.value.size() == 1 &&
          other.value[0] > 1e-3;
      });
    };
    for (const ProbeQuantity& quantity : probe.record.quantities)
    {
      const NamedImage* buffer = quantity.value.size() == 1 ? frame.find(quantity.name) : nullptr;
      const bool techniqueBuffer = std::any_of(technique.buffers.begin(), technique.buffers.end(),
        [&](const BufferSpec& spec) { return spec.name == quantity.name; });
      if (buffer == nullptr || !techniqueBuffer || buffer->image.components != 1 || illConditioned(quantity.name))
      {
        continue;
      }
      const double gpu = buffer->image.at(probe.pixel.x, probe.pixel.y);
      EXPECT_NEAR(quantity.value[0], gpu, 1e-3 * std::max(1.0, std::abs(gpu)))
        << label << ": recorded " << quantity.name << " differs from the GPU buffer";
    }
  }
  EXPECT_GT(agreedUnambiguous, 0) << param.dataset << " " << param.technique << ": every probed pixel was ambiguous";
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, ProbeAgreement, testing::ValuesIn(probeCases()), test::datasetTechniqueName);

// Issue 31: the algorithm diagrams of hard, pcf, lvsm, msm, convsm, ss08 and izb draw numbers they compute from the record; on
// a rendered frame these are what the GPU computed at the pixel: lvsm's layer (found from the recorded layer ends)
// and warp equal its `layer` and `warped_depth` buffers; the lit share of hard's and pcf's compared texels, msm's
// 1 - weight in front of the receiver, convsm's clamp(scale f(d_s)) and ss08's blend of its two levels'
// visibilities (§4.2) and izb's "lit unless a tested triangle covers the sample" equal the GPU's visibility within the
// technique's probe tolerance. Explicit map size: the default is changing to `auto`.
TEST(Probe, AlgorithmDiagramsDrawWhatTheGpuComputed)
{
  const Scene scene = test::loadDataset("stacked-occluders");
  const struct
  {
    const char* technique;
    ProbePanel panel;
  } cases[] = { { "hard", ProbePanel::Comparisons }, { "pcf", ProbePanel::Comparisons }, { "lvsm", ProbePanel::Layers },
    { "msm", ProbePanel::MomentBound }, { "convsm", ProbePanel::Fourier }, { "ss08", ProbePanel::LevelBlend },
    { "izb", ProbePanel::IrregularTexel } };
  for (const auto& testCase : cases)
  {
    // izb has no shadow map: its grid's size instead.
    const bool isIzb = std::string(testCase.technique) == "izb";
    const FrameResult frame =
      test::renderDataset(scene, testCase.technique, 96, 96, { isIzb ? "grid_size=256" : "shadow_map_size=256" });
    int checked = 0;
    for (const PixelKind kind : { PixelKind::Penumbra, PixelKind::Umbra, PixelKind::Lit })
    {
      const std::vector<glm::ivec2> candidates = pixelsOfKind(frame, scene.lights.front(), kind);
      for (std::size_t i = 0; i < std::min<std::size_t>(candidates.size(), 3); ++i)
      {
        const ProbeResult probe = probePixel(frame, scene, 0, candidates[(2 * i + 1) * candidates.size() / 6]);
        if (!probe.outcome.evaluated || !probe.outcome.ambiguity.empty())
        {
          continue;
        }
        const std::string label = format(testCase.technique, " ", kindName(kind), " pixel ", probe.pixel.x, ",", probe.pixel.y);
        const ProbeFigureDrawing drawing = drawProbeFigure(probe, frame, scene);
        if (std::string(testCase.technique) == "ss08" && !drawing.layout.rect(testCase.panel).has_value())
        {
          // A pixel decided before any back-projection (lit or umbra by its depth range) blends no levels.
          EXPECT_EQ(probe.record.find("level_visibility"), nullptr) << label;
          continue;
        }
        ASSERT_TRUE(drawing.layout.rect(testCase.panel).has_value()) << label << ": no diagram";
        const double gpu = probe.gpuVisibility;
        const double tolerance = probe.outcome.tolerance;
        const std::string technique = testCase.technique;
        if (technique == "lvsm")
        {
          const std::optional<double> layer = drawing.drawnValue(ProbePanel::Layers, "layer");
          const std::optional<double> warped = drawing.drawnValue(ProbePanel::Layers, "warped_depth");
          ASSERT_TRUE(layer && warped) << label;
          const int x = probe.pixel.x;
          const int y = probe.pixel.y;
          EXPECT_EQ(*layer, frame.find("layer")->image.at(x, y)) << label;
          EXPECT_NEAR(*warped, frame.find("warped_depth")->image.at(x, y), 1e-3) << label;
          std::cout << "[ measured ] " << label << ": layer drawn " << *layer << ", GPU " << frame.find("layer")->image.at(x, y)
                    << "; warped drawn " << *warped << ", GPU " << frame.find("warped_depth")->image.at(x, y) << "\n";
        }
        else
        {
          double drawnVisibility = 0.0;
          if (technique == "msm")
          {
            drawnVisibility = 1.0 - drawing.drawnValue(ProbePanel::MomentBound, "shadow_intensity").value();
          }
          else if (technique == "ss08")
          {
            drawnVisibility = drawing.drawnValue(ProbePanel::LevelBlend, "visibility").value();
          }
          else if (technique == "izb")
          {
            drawnVisibility = drawing.drawnValue(ProbePanel::IrregularTexel, "visibility").value();
          }
          else if (technique == "convsm")
          {
            const double f = drawing.drawnValue(ProbePanel::Fourier, "reconstruction").value();
            EXPECT_NEAR(f, probe.record.find("reconstruction")->value[0], 1e-12) << label;
            drawnVisibility = std::clamp(probe.record.find("reconstruction_scale")->value[0] * f, 0.0, 1.0);
          }
          else
          {
            drawnVisibility = drawing.drawnValue(ProbePanel::Comparisons, "lit_fraction").value();
          }
          EXPECT_NEAR(drawnVisibility, gpu, tolerance) << label;
          std::cout << "[ measured ] " << label << ": drawn visibility " << drawnVisibility << ", GPU " << gpu
                    << " (tolerance " << tolerance << ")\n";
        }
        ++checked;
      }
    }
    EXPECT_GE(checked, std::string(testCase.technique) == "ss08" ? 1 : 3)
      << testCase.technique << ": too few unambiguous pixels with the diagram";
    if (std::string(testCase.technique) != "lvsm")
    {
      continue;
    }
    // The ground's pixels all lie in the last layer (one depth under this light): also one pixel of every other
    // layer the GPU wrote (the occluders' tops), found from the recorded ends as the GPU found it.
    const ImageF& gpuLayer = frame.find("layer")->image;
    std::set<int> layersChecked;
    for (int y = 0; y < gpuLayer.height; ++y)
    {
      for (int x = 0; x < gpuLayer.width; ++x)
      {
        const int layer = int(std::lround(gpuLayer.at(x, y)));
        if (layer < 0 || layersChecked.count(layer) != 0 || frame.find("coverage")->image.at(x, y) <= 0.5f)
        {
          continue;
        }
        const ProbeResult probe = probePixel(frame, scene, 0, { x, y });
        if (!probe.outcome.evaluated || !probe.outcome.ambiguity.empty())
        {
          continue;
        }
        const std::optional<double> drawn =
          drawProbeFigure(probe, frame, scene).drawnValue(ProbePanel::Layers, "layer");
        ASSERT_TRUE(drawn.has_value()) << "lvsm pixel " << x << "," << y;
        EXPECT_EQ(*drawn, double(layer)) << "lvsm pixel " << x << "," << y;
        std::cout << "[ measured ] lvsm pixel " << x << "," << y << ": layer drawn " << *drawn << ", GPU " << layer << "\n";
        layersChecked.insert(layer);
      }
    }
    EXPECT_GE(layersChecked.size(), 2u) << "lvsm: the frame should hold receivers in two layers at least";
  }
}

// The pixel's footprint in a warped map (survey §4.2): hard with warp=lispsm on deep-view, the nearest ground pixel
// of the middle column and the middle one of its ground pixels (the farthest touches the horizon: its upper corners'
// rays never meet the ground, and the probe draws no footprint; next to it one pixel spans depths so far apart that
// its footprint is no longer the linear one Eq. 2 measures). The footprint's corners are the pixel's corners projected through the warp,
// so its sides are the map's texels per pixel step (the Jacobian J that Eq. 2 inverts): one over the inverse's
// columns is texel_ratio_s and _t, the buffers' values at the pixel, to the curvature of the warp across one pixel.
// The texel the pixel reads lies inside it. Near the eye the warp spends more texels on the pixel than the
// uniform map of the same size.
TEST(Probe, WarpedMapShowsThePixelFootprintInTheWarpedSpace)
{
  const Scene scene = test::loadDataset("deep-view");
  double uniformNearArea = 0.0;
  for (const std::string warp : { "none", "lispsm" })
  {
    const FrameResult frame = test::renderDataset(scene, "hard", 64, 64, { "shadow_map_size=512", "warp=" + warp });
    const ImageF& position = frame.find("position")->image;
    const ImageF& coverage = frame.find("coverage")->image;
    std::vector<glm::ivec2> pixels;
    const int x = 32;
    for (int y = 0; y < 64; ++y)
    {
      if (coverage.at(x, y) > 0.5f && std::abs(position.at(x, y, 1)) < 1e-4)
      {
        pixels.push_back({ x, y });
      }
    }
    ASSERT_GE(pixels.size(), 10u) << warp;
    EXPECT_TRUE(probePixel(frame, scene, 0, pixels.back()).record.mapPolygons.empty()) << warp;
    for (const glm::ivec2 pixel : { pixels.front(), pixels[pixels.size() / 2] })
    {
      const ProbeResult probe = probePixel(frame, scene, 0, pixel);
      ASSERT_EQ(probe.record.mapPolygons.size(), 1u) << warp;
      const std::vector<glm::dvec2>& corners = probe.record.mapPolygons.front().points;
      ASSERT_EQ(corners.size(), 4u);
      // Columns of J: one pixel step along x and along y, in texels; its inverse's columns are one s and one t
      // texel step, in pixels.
      const glm::dvec2 stepX = 0.5 * ((corners[1] - corners[0]) + (corners[2] - corners[3]));
      const glm::dvec2 stepY = 0.5 * ((corners[3] - corners[0]) + (corners[2] - corners[1]));
      const double determinant = stepX.x * stepY.y - stepY.x * stepX.y;
      const double ratioS = glm::length(glm::dvec2(stepY.y, -stepX.y)) / std::abs(determinant);
      const double ratioT = glm::length(glm::dvec2(-stepY.x, stepX.x)) / std::abs(determinant);
      const double bufferS = frame.find("texel_ratio_s")->image.at(pixel.x, pixel.y);
      const double bufferT = frame.find("texel_ratio_t")->image.at(pixel.x, pixel.y);
      const ProbeQuantity* recordedT = probe.record.find("texel_ratio_t");
      ASSERT_NE(recordedT, nullptr);
      std::cout << "[ measured ] warp=" << warp << " pixel " << pixel.x << "," << pixel.y << ": footprint "
                << std::abs(determinant) << " texels, texel_ratio_s/_t from it " << ratioS << " / " << ratioT
                << ", buffers " << bufferS << " / " << bufferT << "\n";
      EXPECT_NEAR(recordedT->value[0], bufferT, 1e-4 * bufferT) << warp;
      EXPECT_NEAR(ratioS / bufferS, 1.0, 0.01) << warp;
      EXPECT_NEAR(ratioT / bufferT, 1.0, 0.01) << warp;
      // The pixel centre's texel (the probe's shadow_map_position) inside the quadrilateral: same side of each edge.
      const ProbeQuantity* centre = probe.record.find("shadow_map_position");
      ASSERT_NE(centre, nullptr);
      const glm::dvec2 c(centre->value[0], centre->value[1]);
      int positive = 0;
      for (int i = 0; i < 4; ++i)
      {
        const glm::dvec2 edge = corners[(i + 1) % 4] - corners[i];
        const glm::dvec2 toCentre = c - corners[i];
        positive += edge.x * toCentre.y - edge.y * toCentre.x > 0.0 ? 1 : 0;
      }
      EXPECT_TRUE(positive == 0 || positive == 4) << warp << ": the pixel's centre lies outside its footprint";
      if (pixel == pixels.front())
      {
        if (warp == "none")
        {
          uniformNearArea = std::abs(determinant);
        }
        else
        {
          EXPECT_GT(std::abs(determinant), 2.0 * uniformNearArea) << "LiSPSM spends more texels on the near pixel";
        }
      }
      // probe.json lists it; probe.vtm has it in the shadow_map block.
      const nlohmann::json json = probeJson(probe, frame, scene);
      ASSERT_EQ(json["map_polygons"].size(), 1u);
      EXPECT_EQ(json["map_polygons"][0]["points"].size(), 4u);
      const vtkSmartPointer<vtkMultiBlockDataSet> data = probeDataSet(probe, frame, scene);
      auto* shadowMap = vtkMultiBlockDataSet::SafeDownCast(data->GetBlock(1));
      ASSERT_NE(shadowMap, nullptr);
      vtkPolyData* footprint = nullptr;
      for (unsigned int b = 0; b < shadowMap->GetNumberOfBlocks(); ++b)
      {
        if (std::string(shadowMap->GetMetaData(b)->Get(vtkCompositeDataSet::NAME())) == "pixel_footprint")
        {
          footprint = vtkPolyData::SafeDownCast(shadowMap->GetBlock(b));
        }
      }
      ASSERT_NE(footprint, nullptr);
      EXPECT_EQ(footprint->GetNumberOfPolys(), 1);
    }
  }
}

// The pixel's footprint in its own cascade's map (survey §4.3.1): hard with 4 log-split cascades on deep-view, one
// ground pixel in each cascade (the middle column's ground pixels, the nearest of each cascade's: farther up a pixel
// spans depths so far apart that its footprint is no longer the linear one Eq. 2 measures). The probe
// reads the view the pixel selected (`cascade` buffer), draws that view's map (shadow_map_depth_c<k>) and names it
// with its split depths; the footprint's corners are in that map's texels, so one over its inverse Jacobian's columns
// gives back the buffers' texel_ratio_s and _t at the pixel, which are that cascade's (CascadeGpu.
// SamplingErrorBuffersUseEachPixelsCascade). Through cascade 0's view (what the probe read before) the farthest
// cascade's pixel would show a several times smaller ratio.
TEST(Probe, CascadedMapShowsThePixelFootprintInItsOwnCascade)
{
  const Scene scene = test::loadDataset("deep-view");
  const FrameResult frame = test::renderDataset(scene, "hard", 64, 256, { "shadow_map_size=256", "cascades=4" });
  ASSERT_TRUE(frame.partitions.has_value());
  const ImageF& position = frame.find("position")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& cascade = frame.find("cascade")->image;
  std::vector<std::vector<glm::ivec2>> perCascade(4);
  const int x = 32;
  for (int y = 0; y < 256; ++y)
  {
    if (coverage.at(x, y) > 0.5f && std::abs(position.at(x, y, 1)) < 1e-4)
    {
      perCascade.at(static_cast<std::size_t>(cascade.at(x, y))).push_back({ x, y });
    }
  }
  double cascade0RatioFar = 0.0, ownRatioFar = 0.0;
  for (std::size_t k = 0; k < perCascade.size(); ++k)
  {
    ASSERT_GE(perCascade[k].size(), 2u) << "cascade " << k;
    const glm::ivec2 pixel = perCascade[k].front();
    const ProbeResult probe = probePixel(frame, scene, 0, pixel);
    const ProbeQuantity* map = findQuantity(probe.record, "sampling error", "shadow_map");
    ASSERT_NE(map, nullptr);
    EXPECT_EQ(map->value.at(0), static_cast<double>(k));
    EXPECT_EQ(map->text, "shadow_map_depth_c" + std::to_string(k));
    const ProbeQuantity* range = findQuantity(probe.record, "sampling error", "view_eye_depth_range");
    ASSERT_NE(range, nullptr);
    EXPECT_DOUBLE_EQ(range->value.at(0), frame.partitions->splits[k]);
    EXPECT_DOUBLE_EQ(range->value.at(1), frame.partitions->splits[k + 1]);
    // What the figure and probe.vtm draw: that cascade's map, named with its split depths.
    const ProbeMap drawn = probeMapOf(frame, pixel);
    EXPECT_EQ(drawn.view, &frame.partitions->views[k]);
    EXPECT_EQ(drawn.depth, &test::lightSpaceArray(frame, "shadow_map_depth_c" + std::to_string(k)));
    EXPECT_NE(drawn.label.find(format("cascade ", k, " of 4")), std::string::npos) << drawn.label;
    ASSERT_EQ(probe.record.mapPolygons.size(), 1u) << "cascade " << k;
    const std::vector<glm::dvec2>& corners = probe.record.mapPolygons.front().points;
    const glm::dvec2 stepX = 0.5 * ((corners[1] - corners[0]) + (corners[2] - corners[3]));
    const glm::dvec2 stepY = 0.5 * ((corners[3] - corners[0]) + (corners[2] - corners[1]));
    const double determinant = stepX.x * stepY.y - stepY.x * stepX.y;
    const double ratioS = glm::length(glm::dvec2(stepY.y, -stepX.y)) / std::abs(determinant);
    const double ratioT = glm::length(glm::dvec2(-stepY.x, stepX.x)) / std::abs(determinant);
    const double bufferS = frame.find("texel_ratio_s")->image.at(pixel.x, pixel.y);
    const double bufferT = frame.find("texel_ratio_t")->image.at(pixel.x, pixel.y);
    std::cout << "[ measured ] cascade " << k << " pixel " << pixel.x << "," << pixel.y << " (" << drawn.label
              << "): footprint " << std::abs(determinant) << " texels, texel_ratio_s/_t from it " << ratioS << " / "
              << ratioT << ", buffers " << bufferS << " / " << bufferT << "\n";
    // To the curvature across one pixel: 1.2 % on the farthest cascade's nearest ground pixel (68 texels).
    EXPECT_NEAR(ratioS / bufferS, 1.0, 0.02) << "cascade " << k;
    EXPECT_NEAR(ratioT / bufferT, 1.0, 0.02) << "cascade " << k;
    // The receiver's texel (the twin's shadow_map_position, in the cascade's map) inside the footprint and the map.
    const ProbeQuantity* centre = probe.record.find("shadow_map_position");
    ASSERT_NE(centre, nullptr);
    const glm::dvec2 c(centre->value[0], centre->value[1]);
    EXPECT_TRUE(c.x > 0.0 && c.y > 0.0 && c.x < 256.0 && c.y < 256.0) << "cascade " << k;
    int positive = 0;
    for (int i = 0; i < 4; ++i)
    {
      const glm::dvec2 edge = corners[(i + 1) % 4] - corners[i];
      const glm::dvec2 toCentre = c - corners[i];
      positive += edge.x * toCentre.y - edge.y * toCentre.x > 0.0 ? 1 : 0;
    }
    EXPECT_TRUE(positive == 0 || positive == 4) << "cascade " << k << ": the pixel's centre lies outside its footprint";
    if (k == 3)
    {
      ownRatioFar = std::max(bufferS, bufferT);
      const ImageF& normal = frame.find("normal")->image;
      const SamplingError other = samplingError(frame.camera, frame.partitions->views[0], pixel.x + 0.5, pixel.y + 0.5,
        glm::dvec3(position.at(pixel.x, pixel.y, 0), position.at(pixel.x, pixel.y, 1), position.at(pixel.x, pixel.y, 2)),
        glm::dvec3(normal.at(pixel.x, pixel.y, 0), normal.at(pixel.x, pixel.y, 1), normal.at(pixel.x, pixel.y, 2)));
      cascade0RatioFar = std::max(other.texelRatioS, other.texelRatioT);
    }
  }
  // The farthest cascade's texels are larger than the first's: through cascade 0's view the far pixel's footprint
  // would span several times more texels (the figure would show the wrong map's sampling).
  EXPECT_LT(3.0 * cascade0RatioFar, ownRatioFar);
}

} // namespace
} // namespace sl
