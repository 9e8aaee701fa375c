// The microrects' GPU build (structures/microrect: vtkSLMicrorectPass, structures/microrect/shaders/MicrorectBuild.glsl)
// against its CPU twin (lightspace/Microrects.h), bit for bit: extents (integers) and depths (min of float
// depths) on random maps with ties, on every map size up to 40 (the loop-free atlas offsets of
// common/MipAtlasLayout.glsl against hsmAtlasOffset), at a size that is not a power of two, and on the shadow map
// of every dataset whose light is an area light, at 128^2 and 512^2. No technique lists the structure yet, so
// the pass runs directly on a map uploaded into a frame of its own, in the shared renderer's GL context (its
// window, with a renderer of this test's that the window does not draw); the export (light_space.vti arrays)
// and the memory are the structure's own functions on that frame.
#include "support/TestSupport.h"

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "gl/vtkSLEglRenderWindow.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "lightspace/Microrects.h"
#include "structures/microrect/MicrorectStructure.h"
#include "structures/microrect/vtkSLMicrorectPass.h"
#include "passes/FrameResources.h"

#include "support/RandomMaps.h"

#include <gtest/gtest.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>
#include <vtk_glew.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// What one run of the pass left, read back.
struct GpuMicrorects
{
  Image<std::uint32_t> extents; // the RGBA16UI atlas
  ImageF depths;                // the R32F atlas
  std::vector<NamedImage> exported;
  std::size_t gpuBytes = 0;
  double wallMs = 0.0;
  double gpuMs = 0.0;
};

// One microrect pass, kept for the whole test process (like the pipeline keeps its passes, so texture reuse
// across maps is exercised too), run in the shared renderer's window. The renderer only gives the pass its
// window (vtkRenderState); it is not added to the window, which therefore never draws it.
class MicrorectBuilder
{
public:
  MicrorectBuilder()
    : window_(test::sharedRenderWindow())
    , renderer_(vtkSmartPointer<vtkRenderer>::New())
    , pass_(vtkSmartPointer<vtkSLMicrorectPass>::New())
  {
    renderer_->SetRenderWindow(window_);
  }
  ~MicrorectBuilder()
  {
    window_->MakeCurrent();
    pass_->ReleaseGraphicsResources(window_);
  }

  GpuMicrorects build(const ImageF& shadowMapLinear, bool withExport = false)
  {
    window_->MakeCurrent();
    const int n = shadowMapLinear.width;
    FrameResources frame;
    frame.hasLightView = true;
    frame.lightView.resolution = n;
    frame.shadowMapLinear = makeFloatTarget(window_, n, n, 1);
    glTextureSubImage2D(frame.shadowMapLinear->GetHandle(), 0, 0, 0, n, n, GL_RED, GL_FLOAT, shadowMapLinear.data.data());
    checkGlErrors("uploading the test's shadow map");
    pass_->SetFrame(&frame);
    pass_->ResetTimer();
    vtkRenderState state(renderer_);
    pass_->Render(&state);
    GpuMicrorects result;
    result.wallMs = pass_->GetWallMilliseconds();
    result.gpuMs = pass_->GetGpuMilliseconds();
    const MicrorectData& data = frame.structureData<MicrorectData>(microrectStructure().name);
    result.extents = readUnsignedTextureExact(data.extentTexture, 4);
    result.depths = readFloatTexture(data.depthTexture, 1);
    result.gpuBytes = microrectStructure().gpuBytes(frame);
    if (withExport)
    {
      FrameResult unused;
      result.exported = microrectStructure().exportImages(frame, unused);
    }
    pass_->SetFrame(nullptr);
    return result;
  }

private:
  vtkSLEglRenderWindow* window_; // owned by the shared renderer, which outlives this (constructed first)
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkSLMicrorectPass> pass_;
};

MicrorectBuilder& builder()
{
  static MicrorectBuilder instance;
  return instance;
}

using test::randomMapWithTies;

// Atlas texels whose extent or depth bits differ between the GPU and the CPU twin (unused texels included: 0).
int differingTexels(const GpuMicrorects& gpu, const Microrects& cpu)
{
  const Image<std::uint32_t> extents = cpu.extentAtlas();
  const ImageF depths = cpu.depthAtlas();
  EXPECT_EQ(gpu.extents.width, extents.width);
  EXPECT_EQ(gpu.depths.width, depths.width);
  if (gpu.extents.data.size() != extents.data.size() || gpu.depths.data.size() != depths.data.size())
  {
    return -1;
  }
  int differing = 0;
  for (std::size_t i = 0; i < depths.pixelCount(); ++i)
  {
    const bool sameExtent = std::equal(extents.data.begin() + static_cast<std::ptrdiff_t>(4 * i),
      extents.data.begin() + static_cast<std::ptrdiff_t>(4 * i + 4),
      gpu.extents.data.begin() + static_cast<std::ptrdiff_t>(4 * i));
    const bool sameDepth = std::memcmp(&depths.data[i], &gpu.depths.data[i], sizeof(float)) == 0;
    differing += (sameExtent && sameDepth) ? 0 : 1;
  }
  return differing;
}

TEST(MicrorectGpu, EqualsTheCpuBuildBitForBitOnRandomMapsWithTies)
{
  for (const int size : { 128, 200, 512 })
  {
    for (const bool blocks : { false, true })
    {
      const ImageF map = randomMapWithTies(size, 101u + static_cast<unsigned>(size), blocks);
      const GpuMicrorects gpu = builder().build(map);
      const int differing = differingTexels(gpu, Microrects::build(map));
      EXPECT_EQ(differing, 0) << size << "^2 " << (blocks ? "blocks" : "independent texels");
      std::cout << "[ measured ] " << size << "^2 " << (blocks ? "blocks" : "independent") << ": " << differing
                << " of " << size * size << " atlas texels differ from the CPU twin\n";
    }
  }
}

// Every map side 1..40: the atlas offsets the GLSL computes in closed form (bitCount) against the CPU's sums,
// and the edge cases of the rule (levels of odd sizes, where C, G or the diagonal partner is missing).
TEST(MicrorectGpu, EqualsTheCpuBuildOnEveryMapSideUpTo40)
{
  int failing = 0;
  for (int size = 1; size <= 40; ++size)
  {
    const ImageF map = randomMapWithTies(size, static_cast<unsigned>(size), size % 2 == 0);
    const int differing = differingTexels(builder().build(map), Microrects::build(map));
    EXPECT_EQ(differing, 0) << size << "^2";
    failing += differing != 0 ? 1 : 0;
  }
  std::cout << "[ measured ] map sides 1..40: " << failing << " differ from the CPU twin\n";
}

// The shadow maps of the datasets (rendered by `hard`, which only needs the map), uploaded as they were read back.
TEST(MicrorectGpu, EqualsTheCpuBuildOnEveryAreaLightDatasetsShadowMap)
{
  int datasets = 0;
  for (const std::string& name : test::datasetNames())
  {
    const Scene scene = test::loadDataset(name);
    if (scene.lights.empty() || scene.lights.front().type != LightType::Area)
    {
      continue;
    }
    ++datasets;
    for (const int size : { 128, 512 })
    {
      const FrameResult frame =
        test::renderDataset(scene, "hard", 32, 32, { "shadow_map_size=" + std::to_string(size) });
      const ImageF& map = test::lightSpaceArray(frame, "shadow_map_depth");
      ASSERT_EQ(map.width, size) << name;
      const Microrects cpu = Microrects::build(map);
      const int differing = differingTexels(builder().build(map), cpu);
      EXPECT_EQ(differing, 0) << name << " " << size << "^2";
      // How much larger than a micropatch the level-3 microrects are on a real map.
      double area = 0.0;
      for (const Microrect& m : cpu.levels[3])
      {
        area += (m.hi.x - m.lo.x + 1) * (m.hi.y - m.lo.y + 1);
      }
      std::cout << "[ measured ] " << name << " " << size << "^2: " << differing
                << " atlas texels differ; level-3 mean extent " << area / static_cast<double>(cpu.levels[3].size())
                << " texels (micropatch 64)\n";
    }
  }
  EXPECT_GE(datasets, 6) << "the datasets with an area light";
}

// light_space.vti arrays and GPU memory, from the structure's own export on the built frame.
TEST(MicrorectGpu, ExportsTheAtlasesAndOverlapCountsAndCountsItsMemory)
{
  const int size = 200;
  const ImageF map = randomMapWithTies(size, 9u, true);
  const Microrects cpu = Microrects::build(map);
  const GpuMicrorects gpu = builder().build(map, true);
  std::vector<std::string> expectedNames = { "microrect_extent", "microrect_depth" };
  for (int level = 1; level <= cpu.levelCount(); ++level)
  {
    expectedNames.push_back("microrect_overlap_" + std::to_string(level));
  }
  std::vector<std::string> names;
  for (const NamedImage& image : gpu.exported)
  {
    names.push_back(image.name);
    EXPECT_EQ(image.image.width, size) << image.name;
    EXPECT_EQ(image.image.height, size) << image.name;
  }
  ASSERT_EQ(names, expectedNames);
  const Image<std::uint32_t> extents = cpu.extentAtlas();
  ASSERT_EQ(gpu.exported[0].image.components, 4);
  std::vector<float> extentsAsFloat(extents.data.begin(), extents.data.end());
  EXPECT_EQ(gpu.exported[0].image.data, extentsAsFloat);
  EXPECT_EQ(gpu.exported[1].image.data, cpu.depthAtlas().data);
  for (int level = 1; level <= cpu.levelCount(); ++level)
  {
    EXPECT_EQ(gpu.exported[static_cast<std::size_t>(level) + 1].image.data, cpu.overlapCount(level).data)
      << "microrect_overlap_" << level;
  }
  // Extents RGBA16UI (8 B) and depths R32F (4 B) per atlas texel, plus the R8UI claim scratch over level 1.
  const std::size_t half = static_cast<std::size_t>(hsmLevelSize(HsmLayout::MipMap, size, 1));
  EXPECT_EQ(gpu.gpuBytes, 12u * size * size + half * half);
}

// The pass keeps its textures between frames when the size fits; nothing of an earlier map may leak.
TEST(MicrorectGpu, ReusedTexturesKeepNothingOfThePreviousMap)
{
  const ImageF first = randomMapWithTies(128, 1u, true);
  const ImageF other = randomMapWithTies(128, 2u, false);
  const ImageF larger = randomMapWithTies(200, 3u, true);
  const GpuMicrorects before = builder().build(first);
  builder().build(other);
  const GpuMicrorects again = builder().build(first);
  builder().build(larger);
  const GpuMicrorects afterResize = builder().build(first);
  EXPECT_EQ(again.extents.data, before.extents.data);
  EXPECT_EQ(again.depths.data, before.depths.data);
  EXPECT_EQ(afterResize.extents.data, before.extents.data);
  EXPECT_EQ(afterResize.depths.data, before.depths.data);
  EXPECT_EQ(differingTexels(before, Microrects::build(first)), 0);
}

// The paper's figure is 1.89 ms for a 1024^2 map on an 8800 GTX (§8); here llvmpipe on a shared machine.
TEST(MicrorectGpu, BuildTimeAt1024)
{
  const ImageF map = randomMapWithTies(1024, 4u, true);
  const auto cpuStart = std::chrono::steady_clock::now();
  const Microrects cpu = Microrects::build(map);
  const double cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart).count();
  for (int run = 0; run < 3; ++run)
  {
    const GpuMicrorects gpu = builder().build(map);
    EXPECT_EQ(differingTexels(gpu, cpu), 0) << "run " << run;
    std::cout << "[ measured ] microrects stage at 1024^2, run " << run << (run == 0 ? " (first at this size: textures allocated; programs compiled if first in the process)" : "")
              << ": wall " << gpu.wallMs << " ms, GPU timer " << gpu.gpuMs << " ms; CPU twin " << cpuMs << " ms\n";
  }
}

} // namespace
} // namespace sl
