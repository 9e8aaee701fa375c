// gbp07 (contour back-projection with radial integration): the GLSL against its double-precision twin on
// read-back buffers, and against the closed-form overlap of a parallel square occluder, converging as the
// shadow map's resolution doubles.
#include "structures/hsm/HsmStructure.h"
#include "support/ProbeChecks.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/gbp07/Gbp07Technique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

namespace sl
{
namespace
{

TEST(Gbp07, ConvergesToTheClosedFormAsTheMapResolutionDoubles)
{
  // One square occluder parallel to the light over the ground: the contour is the occluder's outline, so the
  // error is the outline's discretisation (half a texel, back-projected), which halves with the texel.
  const Scene scene = test::loadDataset("planar-occluder");
  const auto exact = [](double x, double z) { return test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z); };
  double previous = 1e300;
  for (const int size : { 128, 256, 512, 1024 })
  {
    const FrameResult frame = test::renderDataset(scene, "gbp07", 128, 128, { "shadow_map_size=" + std::to_string(size) });
    const test::GroundError error = test::groundErrorAgainst(frame, exact);
    std::cout << "[ measured ] gbp07 on planar-occluder, " << size << "^2 map: RMSE " << error.rmse << ", penumbra RMSE "
              << error.penumbraRmse << ", max " << error.maxError << "\n";
    EXPECT_GT(error.penumbra, 1000);
    EXPECT_LT(error.rmse, previous) << size;
    previous = error.rmse;
  }
}

TEST(Gbp07, MatchesTheCpuImplementation)
{
  // Tolerance 1e-3 on visibility: the statuses and edges are identical (pixels with a sample within float
  // rounding of its comparison, a kernel edge at a texel centre or a lit/umbra test at its boundary are
  // counted, not compared); what remains is float back-projection and polygon clipping, ~1e-6 of the light's
  // area per edge, over up to a few hundred edges.
  struct Case
  {
    std::string dataset;
    std::vector<std::string> settings;
  };
  const std::vector<Case> cases = {
    { "planar-occluder", { "shadow_map_size=1024" } },
    { "stacked-occluders", { "shadow_map_size=512" } },
    { "contact", { "shadow_map_size=512", "hsm=mipmap" } },
    { "bunny", { "shadow_map_size=512", "receiver_plane_bias=off", "kernel_refinements=0" } },
    // The Y shadow map (SS08 §6) at 1024^2: kernels wider than 2^b = 4 texels take their ranges from the
    // 256^2 MSSM part (hsmRange's YSM branch), narrower ones from the mip-map levels.
    { "planar-occluder", { "shadow_map_size=1024", "hsm=ysm" } },
  };
  for (const Case& c : cases)
  {
    const Scene scene = test::loadDataset(c.dataset);
    const FrameResult frame = test::renderDataset(scene, "gbp07", 96, 80, c.settings);
    const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
    const Gbp07Settings gbp07Settings = Gbp07Settings::from(frame.parameters);
    const HsmLayout layout = hierarchicalShadowMapSettings(frame.parameters).layout;
    const HierarchicalShadowMap hsm = HierarchicalShadowMap::build(inputs.shadowMapLinear, layout);
    // For the YSM: the twin with the mip-map HSM alone, to count the pixels whose decision the MSSM part changes.
    const HierarchicalShadowMap mipOnly = layout == HsmLayout::Ysm
      ? HierarchicalShadowMap::build(inputs.shadowMapLinear, HsmLayout::MipMap) : HierarchicalShadowMap();
    int changedByYsm = 0;
    const std::string label = test::caseLabel(c.dataset, c.settings);
    int compared = 0;
    int skipped = 0;
    std::map<BackprojectionClass, int> classes; // pixels compared, by the CPU twin's class
    double maxDifference = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const Gbp07Sample cpu = gbp07Reference(inputs, hsm, gbp07Settings, x, y);
        if (!cpu.sample.evaluated)
        {
          continue;
        }
        if (cpu.kernelEdgeMargin < 1e-4 || cpu.sample.depthMargin < 2e-6 || cpu.sample.reachMargin < 1e-5 ||
          cpu.decisionMargin < 1e-5)
        {
          ++skipped;
          continue;
        }
        ASSERT_NE(cpu.classification, BackprojectionClass::OverLoopBudget) << label << ": the test must stay inside llvmpipe's loop budget";
        ++compared;
        ++classes[cpu.classification];
        const double gpu = frame.find("visibility")->image.at(x, y);
        maxDifference = std::max(maxDifference, std::abs(gpu - cpu.sample.visibility));
        EXPECT_NEAR(gpu, cpu.sample.visibility, 1e-3) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("classification")->image.at(x, y), static_cast<float>(cpu.classification)) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("contour_edges")->image.at(x, y), cpu.contourEdges) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("visited_cells")->image.at(x, y), cpu.visitedCells) << label << " pixel " << x << "," << y;
        EXPECT_NEAR(frame.find("kernel_texels")->image.at(x, y), cpu.kernelTexels, 1e-4 * (1.0 + cpu.kernelTexels)) << label;
        if (layout == HsmLayout::Ysm)
        {
          const Gbp07Sample mip = gbp07Reference(inputs, mipOnly, gbp07Settings, x, y);
          changedByYsm += mip.kernelTexels != cpu.kernelTexels || mip.classification != cpu.classification ? 1 : 0;
        }
      }
    }
    if (layout == HsmLayout::Ysm)
    {
      std::cout << "[ measured ] gbp07 " << label << ": " << changedByYsm << " compared pixels whose kernel or class the YSM's "
                << "MSSM part changes from the mip-map HSM's\n";
      EXPECT_GT(changedByYsm, 100) << label << ": the YSM's range queries must be exercised";
    }
    std::cout << "[ measured ] gbp07 " << label << ": compared " << compared << " (lit " << classes[BackprojectionClass::Lit] << ", umbra "
              << classes[BackprojectionClass::Umbra] << ", penumbra " << classes[BackprojectionClass::Penumbra] << "), skipped " << skipped << ", max |gpu - cpu| "
              << maxDifference << "\n";
    EXPECT_GT(compared, 2000) << label;
    EXPECT_LT(skipped, compared / 50) << label;
    EXPECT_GT(classes[BackprojectionClass::Penumbra], 300) << label;
  }
}

TEST(Gbp07, KernelsTheLoopCapCutsShortAreFlaggedExactly)
{
  // Issue 13: the three stacked rectangles of the yfgl09 tests at a 1024^2 map (the default before auto) give kernels of ~400
  // texels, ~160000 dual cells: llvmpipe's cap of 65535 loop iterations cuts the cell loop. The shader flags a
  // pixel whose last cell it never reached; every pixel that differs from the twin must be flagged, and an
  // unflagged pixel must be exact. Another GL may cut nothing, and then nothing may be flagged or differ.
  const Scene scene = loadScene(test::datasetPath("stacked-occluders"), test::wideKernelOverrides());
  const FrameResult frame = test::renderDataset(scene, "gbp07", 16, 12, { "shadow_map_size=1024" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const Gbp07Settings gbp07Settings = Gbp07Settings::from(frame.parameters);
  const HierarchicalShadowMap hsm = HierarchicalShadowMap::build(inputs.shadowMapLinear, HsmLayout::NBuffers);
  int flagged = 0;
  int differing = 0;
  int differingFlagged = 0;
  double maxUnflagged = 0.0;
  double widest = 0.0;
  for (int y = 0; y < 12; ++y)
  {
    for (int x = 0; x < 16; ++x)
    {
      const Gbp07Sample cpu = gbp07Reference(inputs, hsm, gbp07Settings, x, y);
      const bool cut = frame.find("classification")->image.at(x, y) == static_cast<float>(BackprojectionClass::OverLoopBudget);
      flagged += cut ? 1 : 0;
      widest = std::max(widest, cpu.kernelTexels);
      const double difference = std::abs(frame.find("visibility")->image.at(x, y) - cpu.sample.visibility);
      if (difference > 1e-3)
      {
        ++differing;
        differingFlagged += cut ? 1 : 0;
      }
      if (!cut)
      {
        maxUnflagged = std::max(maxUnflagged, difference);
      }
    }
  }
  std::cout << "[ measured ] gbp07 at 1024^2 on " << frame.glRenderer << ": widest kernel " << widest << " texels, " << flagged
            << " of 192 pixels flagged cut short, " << differing << " differ from the twin by > 1e-3 (" << differingFlagged
            << " of them flagged), max |gpu - twin| " << maxUnflagged << " on the others\n";
  EXPECT_GT(widest, 256.0);
  EXPECT_EQ(differingFlagged, differing) << "a pixel differs from the twin without being flagged";
  EXPECT_LE(maxUnflagged, 1e-3);
  EXPECT_EQ(frame.techniqueStatistics.at("cut_short_pixels"), static_cast<double>(flagged));
  if (frame.glRenderer.find("llvmpipe") != std::string::npos)
  {
    EXPECT_GT(differing, 50) << "the case must outrun llvmpipe's loop cap";
  }
}

TEST(Gbp07, ProbeRecordsTheContourEdgesTheGpuCountedAndTheAreaTheyCover)
{
  // `shadowlab probe` (issue 15) on lit, umbra and penumbra pixels of a rendered frame: the replay equals the GPU
  // (visibility within the twin tolerance, classification, kernel width, contour_edges, visited_cells) and the
  // record adds up: one ProbeContourEdge per edge the GPU counted, each one's signed area the radial area of its
  // back-projection, and f(O) A plus the edges' signed areas the occluded area, (1 - V) A for a partial pixel.
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult frame = test::renderDataset(scene, "gbp07", 64, 48, { "shadow_map_size=256" });
  const ShadowMapInputs inputs = test::shadowMapInputs(frame, scene);
  const Gbp07Settings gbp07Settings = Gbp07Settings::from(frame.parameters);
  const HierarchicalShadowMap hsm = buildHierarchicalShadowMap(inputs.shadowMapLinear, frame.parameters);
  const TechniqueDescriptor& technique = findTechnique("gbp07");
  ASSERT_TRUE(static_cast<bool>(technique.probe));
  const ImageF& classes = frame.find("classification")->image;
  int partial = 0;
  // Lit, umbra and penumbra (partial visibility) pixels from all over the frame.
  std::map<BackprojectionClass, int> probed = test::probeBackprojectionPixels(technique, frame, scene,
    [&](glm::ivec2 pixel, BackprojectionClass gpuClass, const ProbeOutcome& outcome, const ProbeRecord& record) {
      const int x = pixel.x;
      const int y = pixel.y;
      const std::string label = "pixel " + std::to_string(x) + "," + std::to_string(y);
      const auto value = [&](const std::string& name) { return test::recordedValue(record, name, label); };
      // The replay is the twin's default run, and the GPU's.
      const Gbp07Sample twin = gbp07Reference(inputs, hsm, gbp07Settings, x, y);
      EXPECT_EQ(outcome.visibility, twin.sample.visibility) << label;
      EXPECT_NEAR(outcome.visibility, frame.find("visibility")->image.at(x, y), outcome.tolerance) << label;
      EXPECT_EQ(value("classification"), classes.at(x, y)) << label;
      EXPECT_EQ(value("contour_edges"), frame.find("contour_edges")->image.at(x, y)) << label;
      EXPECT_EQ(value("visited_cells"), frame.find("visited_cells")->image.at(x, y)) << label;
      EXPECT_NEAR(value("kernel_texels"), frame.find("kernel_texels")->image.at(x, y), 1e-4 * (1.0 + twin.kernelTexels)) << label;
      for (const ProbeQuantity& quantity : record.quantities)
      {
        EXPECT_FALSE(quantity.source.empty()) << label << ": " << quantity.name << " has no source";
      }
      // The range query's nodes decided the class the GPU took.
      const std::string decides = "query: decides " + backprojectionClassLabel(gpuClass);
      EXPECT_TRUE(std::any_of(record.nodes.begin(), record.nodes.end(), [&](const ProbeNode& node) { return node.decision == decides; }))
        << label;
      ASSERT_EQ(record.droppedEdges, 0u) << label;
      EXPECT_EQ(static_cast<double>(record.contourEdges.size()), twin.contourEdges) << label;
      if (gpuClass != BackprojectionClass::Penumbra)
      {
        EXPECT_TRUE(record.contourEdges.empty()) << label;
        EXPECT_EQ(outcome.visibility, gpuClass == BackprojectionClass::Lit ? 1.0 : 0.0) << label;
        return;
      }
      const double h = value("light_half_size");
      const double covered = test::contourCoveredArea(record, h, test::ZeroAreaEdges::Checked, label);
      partial += test::expectCoveredAreaIsOccludedArea(record, covered, outcome.visibility, 4.0 * h * h, label) ? 1 : 0;
      // The marching-squares input: every searched sample once (those over the recorder's cap counted; the light
      // centre's four are recorded before them).
      const auto samples = static_cast<std::size_t>(std::count_if(record.texels.begin(), record.texels.end(),
        [](const ProbeTexel& texel) { return texel.role == "contour sample"; }));
      const auto last = std::find_if(record.quantities.rbegin(), record.quantities.rend(),
        [](const ProbeQuantity& quantity) { return quantity.name == "searched_samples"; }); // the last kernel's
      ASSERT_NE(last, record.quantities.rend()) << label;
      const std::vector<double>& searched = last->value;
      EXPECT_EQ(static_cast<double>(samples + record.droppedTexels), searched[0] * searched[1]) << label;
    });
  std::cout << "[ measured ] gbp07 probe on stacked-occluders: " << probed[BackprojectionClass::Lit] << " lit, "
            << probed[BackprojectionClass::Umbra] << " umbra, " << probed[BackprojectionClass::Penumbra] << " penumbra pixels ("
            << partial << " partial) replayed unambiguous and consistent\n";
  EXPECT_EQ(probed[BackprojectionClass::Lit], 2);
  EXPECT_EQ(probed[BackprojectionClass::Umbra], 2);
  EXPECT_EQ(probed[BackprojectionClass::Penumbra], 6);
  EXPECT_EQ(partial, 6);
}

} // namespace
} // namespace sl
