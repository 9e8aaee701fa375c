// vssm and its hierarchical shadow map: the HSM against its CPU build, the GLSL against the double-precision
// implementation, and the paper's claims (planar exactness, Fig. 3, Fig. 9, §6.4) against closed forms and
// the ray-traced reference.
#include "lightspace/HierarchicalShadowMap.h"
#include "metrics/ErrorMetrics.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"
#include "techniques/vssm/VssmTechnique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>

namespace sl
{
namespace
{

ImageF referenceVisibility(const FrameResult& frame, const Scene& scene, int samples)
{
  ReferenceSettings settings;
  settings.samples = samples;
  return renderReference(test::referenceInputs(frame, scene), settings).visibility;
}

// The table the GPU built, as the CPU reference reads it (the probe reads the frame the same way).
VssmReferenceInputs referenceInputsOf(const FrameResult& frame, const Scene& scene, const ShadowMapInputs& shadowMap)
{
  return vssmReferenceInputsOf(frame, scene, shadowMap);
}

TEST(HierarchicalShadowMap, GpuLevelsEqualTheCpuBuildExactly)
{
  // min and max are exact in float: every level must be bit-identical, both layouts, and a map size that is
  // not a power of two (odd levels keep their last row and column).
  const Scene scene = test::loadDataset("stacked-occluders");
  for (const int size : { 512, 200 })
  {
    for (const std::string layout : { "mipmap", "nbuffers" })
    {
      const FrameResult frame = test::renderDataset(scene, "vssm", 64, 64,
        { "shadow_map_size=" + std::to_string(size), "hsm=" + layout });
      const ImageF& shadowMap = test::lightSpaceArray(frame, "shadow_map_depth");
      const HierarchicalShadowMap cpu =
        HierarchicalShadowMap::build(shadowMap, layout == "nbuffers" ? HsmLayout::NBuffers : HsmLayout::MipMap);
      std::vector<std::pair<ImageF, std::string>> expected;
      if (layout == "mipmap")
      {
        expected.emplace_back(cpu.atlas(), "");
      }
      else
      {
        for (std::size_t level = 1; level < cpu.levels.size(); ++level)
        {
          expected.emplace_back(cpu.levels[level], "_" + std::to_string(level));
        }
      }
      for (const auto& [image, suffix] : expected)
      {
        const ImageF& gpuMin = test::lightSpaceArray(frame, "hsm_min" + suffix);
        const ImageF& gpuMax = test::lightSpaceArray(frame, "hsm_max" + suffix);
        int differing = 0;
        for (int y = 0; y < size; ++y)
        {
          for (int x = 0; x < size; ++x)
          {
            differing += (gpuMin.at(x, y) != image.at(x, y, 0) || gpuMax.at(x, y) != image.at(x, y, 1)) ? 1 : 0;
          }
        }
        EXPECT_EQ(differing, 0) << layout << suffix << " at " << size;
      }
    }
  }
}

TEST(HierarchicalShadowMap, RangeQueriesAgainstBruteForce)
{
  // N-buffers: exact ranges; mip-map: a superset's range (contains the exact one), from at most 4 nodes.
  ImageF depth(100, 100, 1);
  std::mt19937 generator(11u);
  std::uniform_real_distribution<float> value(1.0f, 5.0f);
  for (float& z : depth.data)
  {
    z = value(generator);
  }
  const HierarchicalShadowMap nBuffers = HierarchicalShadowMap::build(depth, HsmLayout::NBuffers);
  const HierarchicalShadowMap mipMap = HierarchicalShadowMap::build(depth, HsmLayout::MipMap);
  std::uniform_int_distribution<int> coordinate(0, 99);
  for (int query = 0; query < 500; ++query)
  {
    const glm::ivec2 a(coordinate(generator), coordinate(generator));
    const glm::ivec2 b(coordinate(generator), coordinate(generator));
    const glm::ivec2 lo = glm::min(a, b);
    const glm::ivec2 hi = glm::max(a, b);
    glm::dvec2 exact(1e300, -1e300);
    for (int y = lo.y; y <= hi.y; ++y)
    {
      for (int x = lo.x; x <= hi.x; ++x)
      {
        exact = glm::dvec2(std::min(exact.x, static_cast<double>(depth.at(x, y))), std::max(exact.y, static_cast<double>(depth.at(x, y))));
      }
    }
    EXPECT_EQ(nBuffers.range(lo, hi), exact) << lo.x << "," << lo.y << " " << hi.x << "," << hi.y;
    int fetches = 0;
    const glm::dvec2 conservative = mipMap.range(lo, hi, &fetches);
    EXPECT_LE(conservative.x, exact.x);
    EXPECT_GE(conservative.y, exact.y);
    EXPECT_LE(fetches, 4);
  }
}

// Pixels whose GPU decision may legitimately differ from the double-precision one (a comparison within
// float rounding of its boundary) are counted, not compared.
bool ambiguous(const VssmSample& cpu)
{
  return cpu.kernelEdgeMargin < 1e-4 || cpu.sample.depthMargin < 2e-6 || cpu.sample.texelEdgeMargin < 1e-4 ||
    cpu.sample.reachMargin < 1e-5 || cpu.decisionMargin < 1e-4;
}

TEST(Vssm, MatchesTheCpuImplementation)
{
  // Tolerance 2e-3 on visibility: the moments come from the same exact integer table, so what remains is
  // float arithmetic in Eq. 1, 4 and 5 (offsets of order the kernel's depth spread, relative error ~1e-6,
  // amplified by Chebyshev's 1 / (variance + offset^2) at most ~1e-7 d / sigma, and the pooled variance is
  // floored at 1e-6 d^2: below 1e-4). Every buffer's value is compared too.
  struct Case
  {
    std::string dataset;
    std::vector<std::string> settings;
  };
  const std::vector<Case> cases = {
    { "stacked-occluders", {} },
    { "stacked-occluders", { "shadow_subdivision=uniform", "blocker_subdivision=adaptive", "hsm=nbuffers" } },
    { "stacked-occluders", { "hsm=ysm" } }, // b = 1 at 512^2: wider early-out kernels read the MSSM part (SS08 §6)
    { "contact", {} },
    { "bunny", { "receiver_plane_bias=off" } },
    { "near-light", { "sat_precision=float_centred", "nonplanar_pcf_taps=3" } },
    // §6.4 per sub-kernel: contact sub-kernels in the adaptive tree and in the uniform grid.
    { "contact", { "contact_test=subkernel_mean" } },
    { "stacked-occluders", { "contact_test=subkernel_mean", "shadow_subdivision=uniform", "contact_threshold=0.05" } },
  };
  for (const Case& c : cases)
  {
    const Scene scene = test::loadDataset(c.dataset);
    std::vector<std::string> settings = { "shadow_map_size=512" };
    settings.insert(settings.end(), c.settings.begin(), c.settings.end());
    const FrameResult frame = test::renderDataset(scene, "vssm", 96, 80, settings);
    const ShadowMapInputs shadowMap = test::shadowMapInputs(frame, scene);
    const VssmReferenceInputs inputs = referenceInputsOf(frame, scene, shadowMap);
    const VssmSettings vssmSettings = VssmSettings::from(frame.parameters);
    const std::string label = test::caseLabel(c.dataset, c.settings);
    int compared = 0;
    int skipped = 0;
    std::map<VssmClass, int> classes; // pixels compared, by the CPU twin's class
    double maxDifference = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const VssmSample cpu = vssmReference(inputs, vssmSettings, x, y);
        if (!cpu.sample.evaluated)
        {
          continue;
        }
        if (ambiguous(cpu))
        {
          ++skipped;
          continue;
        }
        ++compared;
        ++classes[cpu.classification];
        const double gpu = frame.find("visibility")->image.at(x, y);
        maxDifference = std::max(maxDifference, std::abs(gpu - cpu.sample.visibility));
        EXPECT_NEAR(gpu, cpu.sample.visibility, 2e-3) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("classification")->image.at(x, y), static_cast<float>(cpu.classification)) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("subkernels_mean_not_in_front")->image.at(x, y), cpu.subkernelsMeanNotInFront) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("quadtree_nodes_visited")->image.at(x, y), cpu.quadtreeNodesVisited) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("pcf_samples")->image.at(x, y), cpu.pcfSamples) << label << " pixel " << x << "," << y;
        EXPECT_NEAR(frame.find("blocker_kernel_texels")->image.at(x, y), cpu.blockerKernelTexels, 1e-4 * (1.0 + cpu.blockerKernelTexels)) << label;
        EXPECT_NEAR(frame.find("avg_blocker_depth")->image.at(x, y), cpu.averageBlockerDepth, 1e-3 * (1.0 + cpu.averageBlockerDepth)) << label;
        EXPECT_NEAR(frame.find("penumbra_kernel_texels")->image.at(x, y), cpu.penumbraKernelTexels, 1e-2 * (1.0 + cpu.penumbraKernelTexels)) << label;
      }
    }
    std::cout << "[ measured ] vssm " << label << ": compared " << compared << " (lit " << classes[VssmClass::Lit] << ", umbra "
              << classes[VssmClass::Umbra] << ", penumbra " << classes[VssmClass::Penumbra] << ", contact "
              << classes[VssmClass::Contact] << "), skipped " << skipped
              << ", max |gpu - cpu| " << maxDifference << "\n";
    EXPECT_GT(compared, 2000) << label;
    EXPECT_LT(skipped, compared / 10) << label;
    EXPECT_GT(classes[VssmClass::Penumbra] + classes[VssmClass::Contact], 200) << label;
    if (frame.parameters.choice("contact_test") == "subkernel_mean")
    {
      EXPECT_GT(classes[VssmClass::Contact], 50) << label << ": the per-sub-kernel contact path must be exercised";
    }
  }
}

// Covered pixels of `frame` against the reference: RMSE over those selected by `keep`.
double rmseWhere(const ImageF& visibility, const ImageF& reference, const ImageF& coverage,
  const std::function<bool(int, int)>& keep, int* count = nullptr)
{
  double sum = 0.0;
  int pixels = 0;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      if (coverage.at(x, y) > 0.5 && keep(x, y))
      {
        const double error = visibility.at(x, y) - reference.at(x, y);
        sum += error * error;
        ++pixels;
      }
    }
  }
  if (count)
  {
    *count = pixels;
  }
  return pixels > 0 ? std::sqrt(sum / pixels) : 0.0;
}

// Fig. 3's artefact: lit (>= 0.99) where the light is at least 10% hidden.
int incorrectlyLitPixels(const ImageF& visibility, const ImageF& reference, const ImageF& coverage)
{
  int count = 0;
  for (std::size_t i = 0; i < visibility.data.size(); ++i)
  {
    count += coverage.data[i] > 0.5f && visibility.data[i] >= 0.99f && reference.data[i] < 0.9f ? 1 : 0;
  }
  return count;
}

// The first quantity `name` of the groups whose name starts with `groupPrefix` ("" = any), or nullptr.
const ProbeQuantity* findIn(const ProbeRecord& record, const std::string& groupPrefix, const std::string& name)
{
  for (const ProbeQuantity& quantity : record.quantities)
  {
    if (quantity.name == name && quantity.group.rfind(groupPrefix, 0) == 0)
    {
      return &quantity;
    }
  }
  return nullptr;
}

double valueOf(const ProbeRecord& record, const std::string& groupPrefix, const std::string& name)
{
  const ProbeQuantity* quantity = findIn(record, groupPrefix, name);
  if (!quantity || quantity->value.empty())
  {
    throw std::runtime_error("the probe recorded no " + name + " in group " + groupPrefix);
  }
  return quantity->value[0];
}

TEST(Vssm, ProbeRecordsTheStepsTheGpuTook)
{
  // `shadowlab probe` (issue 15) through the registry's probe on an HSM-lit, an HSM-umbra and a penumbra pixel of
  // stacked-occluders whose penumbra kernel the adaptive quad-tree refines (Alg. 2), plus one under uniform n x n
  // sub-kernels. Each must agree with the GPU within the twin tolerance, record the buffers' values under their
  // names equal to the GPU's at the pixel, and record steps consistent with them: as many quad-tree nodes as
  // quadtree_nodes_visited, each refined node followed by its four children, as many sub-kernels classed
  // non-planar (E(x) >= t: lit, refined or PCF) as subkernels_mean_not_in_front, as many PCF taps as pcf_samples, terminal
  // sub-kernels of w_p tiling w_p, their areas by class adding up to Alg. 2's VSMArea / LitArea / PCFArea, and
  // those areas with Eq. 1's bound giving the visibility (Alg. 2 L29-32).
  const Scene scene = test::loadDataset("stacked-occluders");
  const TechniqueDescriptor& descriptor = findTechnique("vssm");
  ASSERT_TRUE(descriptor.probe);
  struct Wanted
  {
    std::string label;
    std::vector<std::string> settings;
    VssmClass classification;
    bool refined; // a penumbra pixel whose w_p has non-planar sub-kernels and PCF taps
  };
  const std::vector<Wanted> wanted = {
    { "lit (HSM)", {}, VssmClass::Lit, false },
    { "umbra (HSM)", { "hsm=nbuffers" }, VssmClass::Umbra, false }, // the mip-map's conservative ranges leave none here
    { "penumbra, adaptive", {}, VssmClass::Penumbra, true },
    { "penumbra, uniform 8 x 8", { "shadow_subdivision=uniform" }, VssmClass::Penumbra, true },
  };
  for (const Wanted& want : wanted)
  {
    std::vector<std::string> settings = { "shadow_map_size=512" };
    settings.insert(settings.end(), want.settings.begin(), want.settings.end());
    const FrameResult frame = test::renderDataset(scene, "vssm", 96, 80, settings);
    const ShadowMapInputs shadowMap = test::shadowMapInputs(frame, scene);
    const VssmReferenceInputs inputs = referenceInputsOf(frame, scene, shadowMap);
    const VssmSettings vssmSettings = VssmSettings::from(frame.parameters);
    const ImageF& classes = frame.find("classification")->image;
    // The first unambiguous pixel of the wanted class (row by row from the bottom).
    std::optional<glm::ivec2> pixel;
    for (int y = 0; y < 80 && !pixel; ++y)
    {
      for (int x = 0; x < 96 && !pixel; ++x)
      {
        if (classes.at(x, y) != static_cast<float>(want.classification))
        {
          continue;
        }
        ProbeRecorder steps;
        const VssmSample cpu = vssmReference(inputs, vssmSettings, x, y, &steps);
        const ProbeQuantity* hsmDecision = findIn(steps.record(), "hsm test", "hsm_decision");
        const auto& kernels = steps.record().kernels;
        const bool pcfInPenumbra = std::any_of(kernels.begin(), kernels.end(), [](const ProbeKernel& kernel) {
          return kernel.role == "penumbra sub-kernel" && kernel.label == "non-planar";
        });
        const bool interesting = want.refined
          ? pcfInPenumbra && cpu.sample.visibility > 0.1 && cpu.sample.visibility < 0.9 &&
            (vssmSettings.shadowSubdivision.scheme != VssmSubdivision::Adaptive || cpu.quadtreeNodesVisited > 5)
          : hsmDecision && hsmDecision->text != "undecided";
        if (cpu.sample.evaluated && !ambiguous(cpu) && cpu.classification == want.classification && interesting)
        {
          pixel = glm::ivec2(x, y);
        }
      }
    }
    ASSERT_TRUE(pixel) << want.label << ": no such pixel in the frame";
    ProbeRecorder recorder;
    const ProbeOutcome outcome = descriptor.probe({ &frame, &scene, 0 }, *pixel, recorder);
    const ProbeRecord& record = recorder.record();
    const std::string where = want.label + " pixel " + std::to_string(pixel->x) + "," + std::to_string(pixel->y);
    const auto gpu = [&](const std::string& name) { return static_cast<double>(frame.find(name)->image.at(pixel->x, pixel->y)); };
    ASSERT_TRUE(outcome.evaluated) << where;
    EXPECT_EQ(outcome.ambiguity, "") << where;
    EXPECT_EQ(outcome.tolerance, 2e-3) << where;
    EXPECT_NEAR(outcome.visibility, gpu("visibility"), outcome.tolerance) << where;
    // The buffers under their names, with Vssm.MatchesTheCpuImplementation's tolerances.
    EXPECT_NEAR(valueOf(record, "result", "visibility"), gpu("visibility"), outcome.tolerance) << where;
    for (const std::string name : { "classification", "subkernels_mean_not_in_front", "quadtree_nodes_visited", "pcf_samples" })
    {
      EXPECT_EQ(valueOf(record, "", name), gpu(name)) << where << ": " << name;
    }
    EXPECT_NEAR(valueOf(record, "", "blocker_kernel_texels"), gpu("blocker_kernel_texels"), 1e-4 * (1.0 + gpu("blocker_kernel_texels"))) << where;
    EXPECT_NEAR(valueOf(record, "", "avg_blocker_depth"), gpu("avg_blocker_depth"), 1e-3 * (1.0 + gpu("avg_blocker_depth"))) << where;
    EXPECT_NEAR(valueOf(record, "", "penumbra_kernel_texels"), gpu("penumbra_kernel_texels"), 1e-2 * (1.0 + gpu("penumbra_kernel_texels"))) << where;
    // The steps.
    ASSERT_EQ(record.droppedNodes + record.droppedTexels, 0u) << where;
    std::map<int, int> nodesByLevel;
    std::map<int, int> refinedByLevel;
    int quadtreeNodes = 0;
    for (const ProbeNode& node : record.nodes)
    {
      if (node.structure == "quadtree")
      {
        ++quadtreeNodes;
        ++nodesByLevel[node.level];
        refinedByLevel[node.level] += node.decision == "descend" ? 1 : 0;
      }
    }
    EXPECT_EQ(quadtreeNodes, gpu("quadtree_nodes_visited")) << where;
    // One root per adaptive step taken (Alg. 2 L3), four children per refined node (Alg. 2 L21: TreeNode.Child).
    const int roots = want.refined ? (frame.parameters.choice("blocker_subdivision") == "adaptive" ? 1 : 0) +
        (frame.parameters.choice("shadow_subdivision") == "adaptive" ? 1 : 0) : 0;
    EXPECT_EQ(nodesByLevel[0], roots) << where;
    for (const auto& [level, count] : nodesByLevel)
    {
      if (level > 0)
      {
        EXPECT_EQ(count, 4 * refinedByLevel[level - 1]) << where << ": level " << level;
      }
    }
    EXPECT_EQ(refinedByLevel[frame.parameters.getInt("shadow_tree_height")], 0) << where << ": leaves are not refined";
    int nonPlanar = 0;
    for (const ProbeQuantity& quantity : record.quantities)
    {
      if (quantity.name == "class" && quantity.group.find("sub-kernel") != std::string::npos)
      {
        nonPlanar += quantity.text == "lit" || quantity.text == "descend" || quantity.text == "non-planar" ? 1 : 0;
      }
    }
    EXPECT_EQ(nonPlanar, gpu("subkernels_mean_not_in_front")) << where;
    int taps = 0;
    for (const ProbeTexel& texel : record.texels)
    {
      taps += texel.role == "non-planar pcf tap" || texel.role == "contact pcf tap" ? 1 : 0;
    }
    EXPECT_EQ(taps, gpu("pcf_samples")) << where;
    const std::string hsmDecision = findIn(record, "hsm test", "hsm_decision") ? findIn(record, "hsm test", "hsm_decision")->text : "";
    if (!want.refined)
    {
      EXPECT_EQ(hsmDecision, want.classification == VssmClass::Lit ? "lit" : "umbra") << where;
      EXPECT_EQ(findIn(record, "blocker sub-kernel", "class"), nullptr) << where << ": decided before any sub-kernel";
      continue;
    }
    EXPECT_EQ(hsmDecision, "undecided") << where;
    const ProbeKernel* penumbra = nullptr;
    std::map<std::string, double> areaByClass;
    for (const ProbeKernel& kernel : record.kernels)
    {
      if (kernel.role == "penumbra")
      {
        penumbra = &kernel;
      }
      if (kernel.role == "penumbra sub-kernel")
      {
        ASSERT_TRUE(penumbra) << where << ": sub-kernels of w_p before w_p";
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(kernel.lo, penumbra->lo)) && glm::all(glm::lessThanEqual(kernel.hi, penumbra->hi))) << where;
        areaByClass[kernel.label] += (kernel.hi.x - kernel.lo.x) * (kernel.hi.y - kernel.lo.y);
      }
    }
    ASSERT_TRUE(penumbra) << where;
    const double kernelArea = (penumbra->hi.x - penumbra->lo.x) * (penumbra->hi.y - penumbra->lo.y);
    EXPECT_EQ(areaByClass["planar"] + areaByClass["lit"] + areaByClass["non-planar"], kernelArea) << where << ": terminal sub-kernels tile w_p";
    EXPECT_EQ(valueOf(record, "visibility", "vsm_area"), areaByClass["planar"]) << where;
    EXPECT_EQ(valueOf(record, "visibility", "lit_area"), areaByClass["lit"]) << where;
    EXPECT_EQ(valueOf(record, "visibility", "pcf_area"), areaByClass["non-planar"]) << where;
    EXPECT_GT(areaByClass["non-planar"], 0.0) << where;
    const double chebyshev = areaByClass["planar"] > 0.0 ? valueOf(record, "visibility", "chebyshev_unoccluded") : 0.0;
    const double reconstructed = (chebyshev * areaByClass["planar"] + areaByClass["lit"] + areaByClass["non-planar"] -
      valueOf(record, "visibility", "pcf_blocked_area")) / kernelArea;
    EXPECT_NEAR(reconstructed, gpu("visibility"), outcome.tolerance) << where << ": Alg. 2 L29-32 from the recorded areas";
    std::cout << "[ measured ] vssm probe " << where << ": " << record.quantities.size() << " quantities, " << quadtreeNodes
              << " quad-tree nodes, " << taps << " PCF taps, twin " << outcome.visibility << ", gpu " << gpu("visibility") << "\n";
  }
}

TEST(Vssm, MatchesPcssForAParallelPlanarOccluder)
{
  // One occluder parallel to the receiver: two depths per kernel, where Chebyshev (Eq. 1) and Eq. 4 are
  // exact, so vssm must give pcss's shadow (both against the closed form, and pixel by pixel).
  const Scene scene = test::loadDataset("planar-occluder");
  const FrameResult vssm = test::renderDataset(scene, "vssm", 128, 128);
  const FrameResult pcss = test::renderDataset(scene, "pcss", 128, 128);
  const auto exact = [](double x, double z) { return test::parallelSquaresVisibility(1.0, 3.0, 1.0, 1.0, x, z); };
  const test::GroundError vssmError = test::groundErrorAgainst(vssm, exact);
  const test::GroundError pcssError = test::groundErrorAgainst(pcss, exact);
  const ImageF& a = vssm.find("visibility")->image;
  const ImageF& b = pcss.find("visibility")->image;
  const ImageF& coverage = vssm.find("coverage")->image;
  double maxDifference = 0.0;
  double sumSquares = 0.0;
  int pixels = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
  {
    if (coverage.data[i] > 0.5f)
    {
      const double difference = std::abs(a.data[i] - b.data[i]);
      maxDifference = std::max(maxDifference, difference);
      sumSquares += difference * difference;
      ++pixels;
    }
  }
  const double rmsDifference = std::sqrt(sumSquares / pixels);
  std::cout << "[ measured ] planar-occluder against the closed form: vssm RMSE " << vssmError.rmse << ", pcss "
            << pcssError.rmse << "; |vssm - pcss| RMS " << rmsDifference << ", max " << maxDifference << "\n";
  EXPECT_GT(vssmError.penumbra, 1000);
  EXPECT_LT(vssmError.rmse, 0.01);
  EXPECT_LT(rmsDifference, 0.01);
  EXPECT_LT(maxDifference, 0.1);
}

TEST(Vssm, RemovesTheIncorrectlyLitPixelsOfSavsmOnStackedOccluders)
{
  // Fig. 9: where a kernel holds several depth layers, SAVSM's whole-kernel E(x) >= t makes it assume lit.
  // On those pixels (savsm found blockers yet p_max = 1) vssm's subdivision must be closer to the ray-traced
  // reference. Over the whole image, Alg. 2 never refines a node whose mean is in front of the receiver, so
  // the adaptive default shares SAVSM's Chebyshev there; the uniform n x n scheme (§5.2) separates the
  // layers and must beat SAVSM overall.
  const Scene scene = test::loadDataset("stacked-occluders");
  const FrameResult savsm = test::renderDataset(scene, "savsm", 128, 128);
  const FrameResult vssm = test::renderDataset(scene, "vssm", 128, 128);
  const FrameResult uniform = test::renderDataset(scene, "vssm", 128, 128, { "shadow_subdivision=uniform" });
  const ImageF reference = referenceVisibility(savsm, scene, 512);
  const ImageF& coverage = savsm.find("coverage")->image;
  const ImageF& pMax = savsm.find("p_max")->image;
  const ImageF& blockerDepth = savsm.find("avg_blocker_depth")->image;
  const auto litAssumption = [&](int x, int y) { return blockerDepth.at(x, y) > 0.0f && pMax.at(x, y) >= 1.0f; };
  const auto all = [](int, int) { return true; };
  int litAssumptionPixels = 0;
  const double savsmThere = rmseWhere(savsm.find("visibility")->image, reference, coverage, litAssumption, &litAssumptionPixels);
  const double vssmThere = rmseWhere(vssm.find("visibility")->image, reference, coverage, litAssumption);
  const double savsmAll = rmseWhere(savsm.find("visibility")->image, reference, coverage, all);
  const double vssmAll = rmseWhere(vssm.find("visibility")->image, reference, coverage, all);
  const double uniformAll = rmseWhere(uniform.find("visibility")->image, reference, coverage, all);
  std::cout << "[ measured ] stacked-occluders vs Embree: on savsm's " << litAssumptionPixels
            << " lit-assumption pixels RMSE savsm " << savsmThere << ", vssm " << vssmThere << "; whole image savsm "
            << savsmAll << ", vssm (m = 5, H = 3) " << vssmAll << ", vssm (m = 5, n = 8) " << uniformAll << "\n";
  EXPECT_GT(litAssumptionPixels, 20);
  EXPECT_LT(vssmThere, 0.6 * savsmThere);
  EXPECT_LT(uniformAll, 0.9 * savsmAll);
}

TEST(Vssm, SubdivisionReducesIncorrectlyLitPixels)
{
  // Fig. 3: without subdivision a non-planar kernel (E(x) >= t) is assumed lit (VSM); with it, the
  // incorrectly lit pixels must drop.
  for (const std::string dataset : { "stacked-occluders", "bunny" })
  {
    const Scene scene = test::loadDataset(dataset);
    const FrameResult without = test::renderDataset(scene, "vssm", 128, 128,
      { "blocker_subdivision=none", "shadow_subdivision=none" });
    const FrameResult with = test::renderDataset(scene, "vssm", 128, 128);
    const ImageF reference = referenceVisibility(with, scene, 256);
    const ImageF& coverage = with.find("coverage")->image;
    const int before = incorrectlyLitPixels(without.find("visibility")->image, reference, coverage);
    const int after = incorrectlyLitPixels(with.find("visibility")->image, reference, coverage);
    std::cout << "[ measured ] " << dataset << ": incorrectly lit pixels without subdivision " << before
              << ", with (m = 5, H = 3) " << after << "\n";
    EXPECT_GT(before, 10) << dataset;
    EXPECT_LT(after, 0.6 * before) << dataset;
  }
}

TEST(Vssm, ContactShadowUnderALargeLightHasNoSatNoise)
{
  // §6.4's hard case: a plate 0.02 above the ground under a large light far away (height 8, side 5.3):
  // kernels of hundreds of texels where blocker and receiver depths differ by a few SAT steps (int32:
  // 10-bit depths at 2048^2). Against the closed form, the contact fallback (3 x 3 bilinear PCF) must keep
  // the ground's max error small in both precisions; through the SAT (contact_threshold = 0) the same
  // pixels are far worse, which is what the fallback exists for.
  const double plateHeight = 0.02;
  const double lightHeight = 8.0;
  const double lightSize = lightHeight / 1.5;
  const Scene scene = loadScene(test::datasetPath("planar-occluder"), { "/objects/1/center/1=" + std::to_string(plateHeight),
    "/lights/0/center/1=" + std::to_string(lightHeight), "/lights/0/size=" + std::to_string(lightSize) });
  const auto exact = [&](double x, double z) {
    return test::parallelSquaresVisibility(lightSize, lightHeight, 1.0, plateHeight, x, z);
  };
  for (const std::string precision : { "int32", "float_centred" })
  {
    // At 2048^2, where the kernels span hundreds of texels (the automatic map of this view is 256^2).
    const FrameResult fallback =
      test::renderDataset(scene, "vssm", 128, 128, { "sat_precision=" + precision, "shadow_map_size=2048" });
    const FrameResult satOnly = test::renderDataset(
      scene, "vssm", 128, 128, { "sat_precision=" + precision, "contact_threshold=0", "shadow_map_size=2048" });
    const test::GroundError withFallback = test::groundErrorAgainst(fallback, exact);
    const test::GroundError throughSat = test::groundErrorAgainst(satOnly, exact);
    const auto& classification = fallback.find("classification")->image.data;
    const auto contactPixels = std::count(classification.begin(), classification.end(), static_cast<float>(VssmClass::Contact));
    std::cout << "[ measured ] contact plate, light far and large, " << precision << ": " << contactPixels
              << " contact pixels; ground max error " << withFallback.maxError << " (RMSE " << withFallback.rmse
              << ") with the §6.4 fallback, " << throughSat.maxError << " (RMSE " << throughSat.rmse << ") through the SAT\n";
    EXPECT_GT(contactPixels, 20) << precision;
    EXPECT_LT(withFallback.maxError, 0.12) << precision;
    EXPECT_GT(throughSat.maxError, 2.0 * withFallback.maxError) << precision;
  }
}

// The §6.4 plate: a 1 x 1 plate `plateHeight` above the ground under a light `lightHeight` high, side
// lightHeight / 1.5 (planar-occluder, moved).
// `extra`: more JSON-pointer overrides (e.g. the camera).
Scene contactPlateScene(double plateHeight, double lightHeight, const std::vector<std::string>& extra = {})
{
  std::vector<std::string> overrides = { "/objects/1/center/1=" + std::to_string(plateHeight),
    "/lights/0/center/1=" + std::to_string(lightHeight), "/lights/0/size=" + std::to_string(lightHeight / 1.5) };
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return loadScene(test::datasetPath("planar-occluder"), overrides);
}

TEST(Vssm, ContactTestReadingsAgainstTheRayTracer)
{
  // §6.4 read two ways (contact_test): blocker_average tests d - z_occ (Eq. 4) once per pixel and filters
  // all of w_p by 3 x 3 jittered bilinear PCF; subkernel_mean tests each normal sub-kernel of w_p on its own
  // SAT mean and filters only those. Both against Embree on the contact dataset and on the §6.4 plate, with
  // the SAT alone (contact_threshold = 0) and subkernel_mean over uniform 8 x 8 sub-kernels for scale.
  // The readings must differ on the pixels either calls contact (else the parameter does nothing), each must
  // stay within a bound of the ray tracer, on the plate both must beat the SAT alone where they act (what
  // §6.4 is for), and the default (blocker_average) must be the more accurate of the two, as
  // src/techniques/vssm/README.md says.
  struct Case
  {
    std::string label;
    Scene scene;
    double maxRmse;   // either reading, all covered pixels
    int minDiffering; // contact pixels where the readings differ by more than 0.01
    bool fallbackBeatsSat;
  };
  const std::vector<Case> cases = {
    { "contact", test::loadDataset("contact"), 0.045, 100, false },
    { "plate 0.02 under light 8", contactPlateScene(0.02, 8.0), 0.004, 5, true },
    // The same plate's front edge (z = 0.5) through a 4-degree camera: its ~0.013-wide penumbra, a pixel wide
    // in the view above, spans ~4 pixels here. The map keeps covering the light's footprint (LightView.h).
    { "plate 0.02 under light 8, front edge",
      contactPlateScene(0.02, 8.0, { "/camera/focal_point/2=0.5", "/camera/view_angle=4" }), 0.03, 200, false },
  };
  struct Reading
  {
    std::string label;
    std::vector<std::string> settings;
  };
  const std::vector<Reading> readings = {
    { "blocker_average", { "contact_test=blocker_average" } },
    { "subkernel_mean", { "contact_test=subkernel_mean" } },
    { "SAT alone", { "contact_threshold=0" } },
    { "subkernel_mean over uniform 8 x 8", { "contact_test=subkernel_mean", "shadow_subdivision=uniform" } },
  };
  for (const Case& c : cases)
  {
    std::vector<FrameResult> frames;
    for (const Reading& reading : readings)
    {
      // A 2048^2 map, the default these readings and bounds were measured at (§6.4's contact is a few texels deep:
      // at the automatic 256^2 of this view the plate's contact falls inside one texel and no reading calls it).
      std::vector<std::string> settings = reading.settings;
      settings.push_back("shadow_map_size=2048");
      frames.push_back(test::renderDataset(c.scene, "vssm", 128, 128, settings));
    }
    const ReferenceInputs inputs = test::referenceInputs(frames[0], c.scene);
    ReferenceSettings referenceSettings;
    referenceSettings.samples = 512;
    const ImageF reference = renderReference(inputs, referenceSettings).visibility;
    const ImageF& coverage = inputs.coverage;
    const float contact = static_cast<float>(VssmClass::Contact);
    const ImageF& classesA = frames[0].find("classification")->image;
    const ImageF& classesB = frames[1].find("classification")->image;
    const auto contactPixel = [&](int x, int y) { return classesA.at(x, y) == contact || classesB.at(x, y) == contact; };
    std::vector<ErrorMetrics> metrics;
    std::vector<double> contactRmse;
    int contactPixels = 0;
    for (const FrameResult& frame : frames)
    {
      metrics.push_back(computeErrorMetrics(frame.find("visibility")->image, reference, coverage, coverage));
      contactRmse.push_back(rmseWhere(frame.find("visibility")->image, reference, coverage, contactPixel, &contactPixels));
    }
    const ImageF& a = frames[0].find("visibility")->image;
    const ImageF& b = frames[1].find("visibility")->image;
    int differing = 0;
    double maxDifference = 0.0;
    for (int y = 0; y < a.height; ++y)
    {
      for (int x = 0; x < a.width; ++x)
      {
        if (coverage.at(x, y) > 0.5f && contactPixel(x, y))
        {
          const double difference = std::abs(a.at(x, y) - b.at(x, y));
          maxDifference = std::max(maxDifference, difference);
          differing += difference > 0.01 ? 1 : 0;
        }
      }
    }
    const auto count = [&](const ImageF& classes) { return std::count(classes.data.begin(), classes.data.end(), contact); };
    const auto contactA = count(classesA);
    const auto contactB = count(classesB);
    std::cout << "[ measured ] vssm contact_test on " << c.label << " vs Embree (512 samples), RMSE / penumbra RMSE ("
              << metrics[0].penumbra.pixels << " px) / RMSE on the " << contactPixels << " px either reading calls contact:";
    for (std::size_t i = 0; i < readings.size(); ++i)
    {
      std::cout << (i ? "; " : " ") << readings[i].label << " " << metrics[i].covered.rmse << " / "
                << metrics[i].penumbra.rmse << " / " << contactRmse[i];
    }
    std::cout << ". Contact px: blocker_average " << contactA << ", subkernel_mean " << contactB
              << " (with a contact sub-kernel); readings differ by > 0.01 on " << differing << " of them (max "
              << maxDifference << ")\n";
    EXPECT_GT(contactB, 0) << c.label;
    EXPECT_GE(differing, c.minDiffering) << c.label;
    EXPECT_LT(metrics[0].covered.rmse, c.maxRmse) << c.label;
    EXPECT_LT(metrics[1].covered.rmse, c.maxRmse) << c.label;
    EXPECT_LT(metrics[0].covered.rmse, metrics[1].covered.rmse) << c.label;
    if (c.fallbackBeatsSat)
    {
      EXPECT_GT(contactA, 20) << c.label;
      EXPECT_LT(contactRmse[0], 0.5 * contactRmse[2]) << c.label;
      EXPECT_LT(contactRmse[1], 0.5 * contactRmse[2]) << c.label;
    }
  }
}

TEST(Vssm, FiniteWhenVarianceVanishesBlockersTouchOrKernelsLeaveTheMap)
{
  struct Case
  {
    std::string dataset;
    double lightSize; // 0: the dataset's
    std::vector<std::string> settings;
  };
  const std::vector<Case> cases = {
    { "planar-occluder", 0.0, { "min_variance=0", "lit_variance_threshold=0" } }, // variance -> 0
    { "contact", 0.0, { "contact_threshold=0", "min_variance=0" } },              // z_avg = t at the contact
    { "stacked-occluders", 40.0, { "hsm=nbuffers", "shadow_map_size=256" } },     // kernels far outside the map
    { "near-light", 0.0, { "shadow_subdivision=uniform", "shadow_uniform_n=16", "blocker_subdivision=adaptive", "blocker_tree_height=5" } },
  };
  for (const Case& c : cases)
  {
    Scene scene = test::loadDataset(c.dataset);
    if (c.lightSize > 0.0)
    {
      scene.lights[0].size = c.lightSize;
    }
    const FrameResult frame = test::renderDataset(scene, "vssm", 96, 80, c.settings);
    for (const auto* list : { &frame.buffers, &frame.lightSpace })
    {
      for (const NamedImage& named : *list)
      {
        const auto bad = std::count_if(named.image.data.begin(), named.image.data.end(), [](float v) { return !std::isfinite(v); });
        EXPECT_EQ(bad, 0) << c.dataset << ": " << named.name;
      }
    }
    for (const float value : frame.find("visibility")->image.data)
    {
      ASSERT_TRUE(value >= 0.0f && value <= 1.0f) << c.dataset << ": " << value;
    }
  }
}

} // namespace
} // namespace sl
