// vssm and its hierarchical shadow map: the HSM against its CPU build, the GLSL against the double-precision
// implementation, and the paper's claims (planar exactness, Fig. 3, Fig. 9, §6.4) against closed forms and
// the ray-traced reference.
#include "lightspace/HierarchicalShadowMap.h"
#include "metrics/ErrorMetrics.h"
#include "support/TestSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/vssm/VssmTechnique.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

namespace sl
{
namespace
{

const ImageF& lightSpaceArray(const FrameResult& frame, const std::string& name)
{
  for (const NamedImage& named : frame.lightSpace)
  {
    if (named.name == name)
    {
      return named.image;
    }
  }
  throw std::runtime_error("no light-space array " + name);
}

ImageF referenceVisibility(const FrameResult& frame, const Scene& scene, int samples)
{
  ReferenceSettings settings;
  settings.samples = samples;
  return renderReference(test::referenceInputs(frame, scene), settings).visibility;
}

// The table the GPU built, as the CPU reference reads it.
VssmReferenceInputs referenceInputsOf(const FrameResult& frame, const Scene& scene, const ShadowMapInputs& shadowMap)
{
  ImageF floatTable;
  if (!frame.integerSummedAreaTable)
  {
    const ImageF& sumZ = lightSpaceArray(frame, "sat_z");
    const ImageF& sumZ2 = lightSpaceArray(frame, "sat_z2");
    floatTable = ImageF(sumZ.width, sumZ.height, 2);
    for (std::size_t i = 0; i < sumZ.data.size(); ++i)
    {
      floatTable.data[i * 2] = sumZ.data[i];
      floatTable.data[i * 2 + 1] = sumZ2.data[i];
    }
  }
  return vssmReferenceInputs(shadowMap, frame.parameters, frame.integerSummedAreaTable, floatTable, scene.bounds().radius());
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
      const ImageF& shadowMap = lightSpaceArray(frame, "shadow_map_depth");
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
        const ImageF& gpuMin = lightSpaceArray(frame, "hsm_min" + suffix);
        const ImageF& gpuMax = lightSpaceArray(frame, "hsm_max" + suffix);
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
    { "contact", {} },
    { "bunny", { "receiver_plane_bias=off" } },
    { "near-light", { "sat_precision=float_centred", "nonplanar_pcf_taps=3" } },
  };
  for (const Case& c : cases)
  {
    const Scene scene = test::loadDataset(c.dataset);
    std::vector<std::string> settings = { "shadow_map_size=512" };
    settings.insert(settings.end(), c.settings.begin(), c.settings.end());
    const FrameResult frame = test::renderDataset(scene, "vssm", 96, 80, settings);
    const ShadowMapInputs shadowMap = test::shadowMapInputs(frame, scene);
    const VssmReferenceInputs inputs = referenceInputsOf(frame, scene, shadowMap);
    std::string label = c.dataset;
    for (const std::string& setting : c.settings)
    {
      label += " " + setting;
    }
    int compared = 0;
    int skipped = 0;
    int classes[5] = { 0, 0, 0, 0, 0 };
    double maxDifference = 0.0;
    for (int y = 0; y < 80; ++y)
    {
      for (int x = 0; x < 96; ++x)
      {
        const VssmSample cpu = vssmReference(inputs, frame.parameters, x, y);
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
        ++classes[static_cast<int>(cpu.classification)];
        const double gpu = frame.find("visibility")->image.at(x, y);
        maxDifference = std::max(maxDifference, std::abs(gpu - cpu.sample.visibility));
        EXPECT_NEAR(gpu, cpu.sample.visibility, 2e-3) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("classification")->image.at(x, y), static_cast<float>(cpu.classification)) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("nonplanar_subkernels")->image.at(x, y), cpu.nonplanarSubkernels) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("quadtree_nodes_visited")->image.at(x, y), cpu.quadtreeNodesVisited) << label << " pixel " << x << "," << y;
        EXPECT_EQ(frame.find("pcf_samples")->image.at(x, y), cpu.pcfSamples) << label << " pixel " << x << "," << y;
        EXPECT_NEAR(frame.find("blocker_kernel_texels")->image.at(x, y), cpu.blockerKernelTexels, 1e-4 * (1.0 + cpu.blockerKernelTexels)) << label;
        EXPECT_NEAR(frame.find("avg_blocker_depth")->image.at(x, y), cpu.averageBlockerDepth, 1e-3 * (1.0 + cpu.averageBlockerDepth)) << label;
        EXPECT_NEAR(frame.find("penumbra_kernel_texels")->image.at(x, y), cpu.penumbraKernelTexels, 1e-2 * (1.0 + cpu.penumbraKernelTexels)) << label;
      }
    }
    std::cout << "[ measured ] vssm " << label << ": compared " << compared << " (lit " << classes[1] << ", umbra "
              << classes[2] << ", penumbra " << classes[3] << ", contact " << classes[4] << "), skipped " << skipped
              << ", max |gpu - cpu| " << maxDifference << "\n";
    EXPECT_GT(compared, 2000) << label;
    EXPECT_LT(skipped, compared / 10) << label;
    EXPECT_GT(classes[3] + classes[4], 200) << label;
  }
}

} // namespace
} // namespace sl
