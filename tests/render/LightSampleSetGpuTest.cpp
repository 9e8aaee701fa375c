// The light-sample set's GLSL twin (shaders/common/LightSampleSet.glsl) against the CPU (lightspace/
// LightSampleSet.h), through the structure's own build pass and binding (structures/lightsamples): for every
// pattern and N = 16, 64 (and 256 on a smaller image), lightSampleShift and lightSampleUnit equal the CPU bit for
// bit at every (pixel, sample) of a 64 x 64 image, at the origin and at large pixel coordinates (the hash's high
// bits), and lightSamplePoint equals LightSampleSet::point within 1e-6 of the light's scale on a square and a
// disk light. Also: the pass uploads only when the settings change, the export is the base points, the memory
// N x 8 bytes. No technique is needed: the pass runs on a frame of its own in the shared renderer's GL context,
// and a full-screen pass writes, for texel (x N + k, y), sample k of pixel (x, y) + origin.
#include "support/TestSupport.h"

#include "core/Image.h"
#include "frame/FrameResult.h"
#include "gl/GlResources.h"
#include "gl/ShaderLibrary.h"
#include "gl/vtkSLEglRenderWindow.h"
#include "lightspace/LightSampleSet.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "structures/lightsamples/vtkSLLightSamplePass.h"
#include "passes/FrameResources.h"
#include "passes/FullScreenQuad.h"
#include "passes/ScopedRenderTarget.h"

#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkRenderState.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkSmartPointer.h>
#include <vtkTextureObject.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

// The probe's fragment shader: the lookup as a technique includes it, then a main that writes sample k of pixel
// (x, y) + origin to texel (x N + k, y): unit point and shift, and the world point.
const char* const kProbeMain = R"(
uniform int probeOriginX;
uniform int probeOriginY;
layout(location = 0) out vec4 outUnitAndShift;
layout(location = 1) out vec4 outPoint;
void main()
{
  ivec2 texel = ivec2(gl_FragCoord.xy);
  int index = texel.x % LIGHT_SAMPLE_COUNT;
  ivec2 pixel = ivec2(texel.x / LIGHT_SAMPLE_COUNT + probeOriginX, texel.y + probeOriginY);
  outUnitAndShift = vec4(lightSampleUnit(pixel, index), lightSampleShift(pixel));
  outPoint = vec4(lightSamplePoint(pixel, index), 0.0);
}
)";

struct GpuSamples
{
  ImageF unitAndShift; // (N width) x height, RGBA: unit.xy, shift.xy
  ImageF point;        // RGBA: world xyz
  std::vector<NamedImage> exported;
  std::size_t gpuBytes = 0;
};

// The structure's pass, kept for the whole process (as the pipeline keeps it), and a full-screen probe, in the
// shared renderer's window; the renderer only hands the pass its window (vtkRenderState) and never draws.
class SampleSetProbe
{
public:
  SampleSetProbe()
    : window_(test::sharedRenderWindow())
    , renderer_(vtkSmartPointer<vtkRenderer>::New())
    , pass_(vtkSmartPointer<vtkSLLightSamplePass>::New())
  {
    renderer_->SetRenderWindow(window_);
  }
  ~SampleSetProbe()
  {
    window_->MakeCurrent();
    quad_.releaseGraphicsResources(window_);
    framebuffer_->ReleaseGraphicsResources(window_);
    pass_->ReleaseGraphicsResources(window_);
  }

  int uploads() const { return pass_->GetUploadCount(); }

  GpuSamples run(const std::string& pattern, int count, std::uint32_t seed, const Light& light, int side,
    glm::ivec2 origin)
  {
    window_->MakeCurrent();
    const LightSpaceStructure& structure = lightSampleSetStructure();
    FrameResources frame;
    frame.light = &light;
    frame.parameters = ParameterValues("light_samples", structure.parameters);
    frame.parameters.set("light_samples=" + pattern);
    frame.parameters.set("samples=" + std::to_string(count));
    frame.parameters.set("sample_seed", seed);
    pass_->SetFrame(&frame);
    pass_->ResetTimer();
    vtkRenderState state(renderer_);
    pass_->Render(&state);
    pass_->SetFrame(nullptr);

    GpuSamples result;
    const auto unitAndShift = makeFloatTarget(window_, side * count, side, 4);
    const auto point = makeFloatTarget(window_, side * count, side, 4);
    {
      const ScopedRenderTarget target(window_, framebuffer_, { unitAndShift, point });
      const std::string source =
        assembleShader("common/LightSampleSet.glsl", structure.shaderDefines(frame)) + kProbeMain;
      vtkShaderProgram* program = quad_.ready(window_, source, "light-sample probe");
      const std::vector<vtkTextureObject*> bound = structure.bind(program, frame);
      EXPECT_EQ(bound.size(), 1u) << "the base-point texture";
      program->SetUniformi("probeOriginX", origin.x);
      program->SetUniformi("probeOriginY", origin.y);
      quad_.render();
      for (vtkTextureObject* texture : bound)
      {
        texture->Deactivate();
      }
    }
    checkGlErrors("light-sample probe");
    result.unitAndShift = readFloatTexture(unitAndShift, 4);
    result.point = readFloatTexture(point, 4);
    FrameResult unused;
    result.exported = structure.exportImages(frame, unused);
    result.gpuBytes = structure.gpuBytes(frame);
    return result;
  }

private:
  vtkSLEglRenderWindow* window_; // owned by the shared renderer, which outlives this (constructed first)
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkSLLightSamplePass> pass_;
  vtkNew<vtkOpenGLFramebufferObject> framebuffer_;
  FullScreenQuad quad_;
};

SampleSetProbe& probe()
{
  static SampleSetProbe instance;
  return instance;
}

bool sameBits(float a, double exact)
{
  const float b = static_cast<float>(exact); // the CPU's values are multiples of 2^-16: exact in float
  return std::memcmp(&a, &b, sizeof a) == 0;
}

Light squareLight()
{
  Light light;
  light.type = LightType::Area;
  light.shape = LightShape::Square;
  light.center = glm::dvec3(0.4, 5.0, -0.7);
  light.normal = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
  light.up = glm::normalize(glm::cross(light.normal, glm::dvec3(1.0, 0.0, 0.0)));
  light.size = 1.3;
  return light;
}

struct SampleSetComparison
{
  int unitMismatches = 0;
  int shiftMismatches = 0;
  double maxPointError = 0.0; // |gpu - cpu| / (|centre| + size)
};

SampleSetComparison compare(const GpuSamples& gpu, const LightSampleSet& cpu, const Light& light, int side, glm::ivec2 origin)
{
  SampleSetComparison result;
  const int count = cpu.count();
  const double scale = glm::length(light.center) + light.size;
  for (int y = 0; y < side; ++y)
  {
    for (int x = 0; x < side; ++x)
    {
      const glm::dvec2 shift = cpu.pixelShift(origin.x + x, origin.y + y);
      for (int k = 0; k < count; ++k)
      {
        const float* texel = &gpu.unitAndShift.data[4 * (static_cast<std::size_t>(y) * side * count + x * count + k)];
        const glm::dvec2 unit = cpu.unitSample(origin.x + x, origin.y + y, k);
        const bool unitSame = sameBits(texel[0], unit.x) && sameBits(texel[1], unit.y);
        if (!unitSame && result.unitMismatches < 3)
        {
          ADD_FAILURE() << lightSamplePatternName(cpu.settings()) << " N=" << count << " pixel " << origin.x + x << ","
                        << origin.y + y << " sample " << k << ": gpu (" << texel[0] << ", " << texel[1] << ") cpu ("
                        << unit.x << ", " << unit.y << ")";
        }
        result.unitMismatches += unitSame ? 0 : 1;
        result.shiftMismatches += (sameBits(texel[2], shift.x) && sameBits(texel[3], shift.y)) ? 0 : 1;
        const float* p = &gpu.point.data[4 * (static_cast<std::size_t>(y) * side * count + x * count + k)];
        const glm::dvec3 expected = cpu.point(light, origin.x + x, origin.y + y, k);
        result.maxPointError =
          std::max(result.maxPointError, glm::length(glm::dvec3(p[0], p[1], p[2]) - expected) / scale);
      }
    }
  }
  return result;
}

TEST(LightSampleSetGpu, TheGlslTwinEqualsTheCpuBitForBitForEveryPattern)
{
  Light disk = squareLight();
  disk.shape = LightShape::Disk;
  disk.size = 2.1;
  int cases = 0;
  for (const std::string& pattern : lightSamplePatternNames())
  {
    int unitMismatches = 0;
    int compared = 0;
    double maxPointError = 0.0;
    for (const int count : { 16, 64, 256 })
    {
      const int side = count == 256 ? 24 : 64; // 256 x 24 texels wide at most: 6144
      const std::uint32_t seed = 7u + static_cast<std::uint32_t>(count);
      const LightSampleSet cpu(lightSampleSetSettings(pattern, count, seed));
      for (const bool onDisk : { false, true })
      {
        const Light light = onDisk ? disk : squareLight();
        for (const glm::ivec2 origin : { glm::ivec2(0, 0), glm::ivec2(1913, 4090) })
        {
          const GpuSamples gpu = probe().run(pattern, count, seed, light, side, origin);
          const SampleSetComparison comparison = compare(gpu, cpu, light, side, origin);
          const std::string label = pattern + " N=" + std::to_string(count) + (onDisk ? " disk" : " square") +
            " origin " + std::to_string(origin.x) + "," + std::to_string(origin.y);
          EXPECT_EQ(comparison.unitMismatches, 0) << label;
          EXPECT_EQ(comparison.shiftMismatches, 0) << label;
          EXPECT_LT(comparison.maxPointError, 1e-6) << label;
          unitMismatches += comparison.unitMismatches;
          compared += side * side * count;
          maxPointError = std::max(maxPointError, comparison.maxPointError);
          ++cases;
        }
      }
    }
    std::cout << "[ measured ] " << pattern << " (N = 16, 64, 256; square and disk; two pixel origins): "
              << unitMismatches << " of " << compared << " unit samples differ from the CPU, lightSamplePoint max error "
              << maxPointError << " of |centre| + size\n";
  }
  EXPECT_EQ(cases, 8 * 3 * 2 * 2);
}

// The export is the base points as the texture holds them, and their offsets on the light; the memory N x 8 B.
TEST(LightSampleSetGpu, ExportsTheBasePointsAndItsMemory)
{
  const Light light = squareLight();
  for (const int count : { 16, 64, 256 })
  {
    const LightSampleSet cpu(lightSampleSetSettings("poisson_4x4", count, 3u));
    const GpuSamples gpu = probe().run("poisson_4x4", count, 3u, light, 4, glm::ivec2(0));
    EXPECT_EQ(gpu.gpuBytes, static_cast<std::size_t>(count) * 8u);
    const NamedImage* base = findNamed(gpu.exported, "light_samples");
    const NamedImage* offsets = findNamed(gpu.exported, "light_sample_offsets");
    ASSERT_TRUE(base && offsets);
    ASSERT_EQ(base->image.width, count);
    ASSERT_EQ(base->image.height, 1);
    ASSERT_EQ(base->image.components, 2);
    ASSERT_EQ(offsets->image.width, count);
    ASSERT_EQ(offsets->image.components, 2);
    int differing = 0;
    double offsetError = 0.0;
    for (int k = 0; k < count; ++k)
    {
      const glm::dvec2 point = cpu.basePoints()[static_cast<std::size_t>(k)];
      differing += (sameBits(base->image.data[2 * k], point.x) && sameBits(base->image.data[2 * k + 1], point.y)) ? 0 : 1;
      const glm::dvec2 offset = lightPlaneOffset(light, point);
      offsetError = std::max(offsetError, glm::length(glm::dvec2(offsets->image.data[2 * k], offsets->image.data[2 * k + 1]) - offset));
    }
    EXPECT_EQ(differing, 0) << "N=" << count;
    EXPECT_LT(offsetError, 1e-6 * light.size) << "N=" << count;
  }
}

// The set is constructed and uploaded again only when a setting changes.
TEST(LightSampleSetGpu, UploadsOnlyWhenTheSettingsChange)
{
  const Light light = squareLight();
  probe().run("grid", 16, 1u, light, 2, glm::ivec2(0));
  const int start = probe().uploads();
  probe().run("grid", 16, 1u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start) << "same settings";
  probe().run("grid", 16, 2u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start + 1) << "another seed";
  probe().run("grid_4x4", 16, 2u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start + 2) << "interleaved";
  probe().run("grid_4x4", 64, 2u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start + 3) << "another count";
  probe().run("stratified_4x4", 64, 2u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start + 4) << "another pattern";
  probe().run("stratified_4x4", 64, 2u, light, 2, glm::ivec2(0));
  EXPECT_EQ(probe().uploads(), start + 4) << "same settings again";
}

} // namespace
} // namespace sl
