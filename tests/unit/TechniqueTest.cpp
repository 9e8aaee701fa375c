// The technique registry and parameter handling: declared tables are consistent, and every bad
// parameter the user can type is rejected with a message naming it.
#include "core/Error.h"
#include "pipeline/ShadowRenderer.h"
#include "techniques/Registry.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/pcf/PcfTechnique.h"

#include <gtest/gtest.h>

#include <set>

namespace sl
{
namespace
{

template <typename Function>
std::string inputErrorMessage(Function function)
{
  try
  {
    function();
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return {};
}

TEST(TechniqueRegistry, DescriptorsAreConsistent)
{
  std::set<std::string> names;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    EXPECT_TRUE(names.insert(technique.name).second) << "duplicate technique " << technique.name;
    EXPECT_FALSE(technique.paper.empty()) << technique.name;
    EXPECT_TRUE(technique.createPass) << technique.name;
    std::set<std::string> parameterNames;
    for (const ParameterSpec& spec : technique.parameters)
    {
      EXPECT_TRUE(parameterNames.insert(spec.name).second) << technique.name << "." << spec.name;
      if (!isAutomaticValue(spec, spec.defaultValue))
      {
        EXPECT_LE(spec.minValue, spec.defaultValue) << technique.name << "." << spec.name;
        EXPECT_LE(spec.defaultValue, spec.maxValue) << technique.name << "." << spec.name;
      }
      EXPECT_FALSE(spec.doc.empty()) << technique.name << "." << spec.name;
      if (!spec.choices.empty())
      {
        EXPECT_EQ(spec.maxValue, static_cast<double>(spec.choices.size() - 1)) << spec.name;
      }
    }
    std::set<std::string> bufferNames;
    for (const BufferSpec& common : commonBufferSpecs())
    {
      bufferNames.insert(common.name);
    }
    for (const BufferSpec& buffer : technique.buffers)
    {
      EXPECT_TRUE(bufferNames.insert(buffer.name).second) << technique.name << " buffer " << buffer.name;
    }
  }
  EXPECT_TRUE(names.count("hard") && names.count("pcf"));
}

TEST(TechniqueRegistry, GridTechniquesStayUnderTheLoopCapAtTheirLargestSettings)
{
  // pcss and savsm loop over max_grid_taps^2 taps in each of their two grids (blocker search, filter) plus one
  // row iteration per grid row: at the range's top that must stay under the loop iterations llvmpipe allows one
  // invocation, or pixels are cut short without a trace (issue 13 measured 256 x 256 grids cut at 2048^2).
  for (const char* name : { "pcss", "savsm" })
  {
    const ParameterSpec* taps = findTechnique(name).findParameter("max_grid_taps");
    ASSERT_NE(taps, nullptr) << name;
    const long widest = static_cast<long>(taps->maxValue);
    EXPECT_LT(2 * (widest * widest + widest), glLoopIterationCap) << name << ": max_grid_taps up to " << widest;
    EXPECT_GE(widest, 148) << name << ": every texel of the 147-texel kernels of the 512^2 benches";
  }
}

TEST(TechniqueRegistry, UnknownTechniqueListsTheAvailableOnes)
{
  const std::string message = inputErrorMessage([] { findTechnique("penumbra-wizard"); });
  EXPECT_NE(message.find("penumbra-wizard"), std::string::npos) << message;
  EXPECT_NE(message.find("hard"), std::string::npos) << message;
  EXPECT_NE(message.find("pcf"), std::string::npos) << message;
}

TEST(ParameterValues, DefaultsAndAssignments)
{
  ParameterValues values = findTechnique("pcf").defaultParameters();
  EXPECT_EQ(values.getInt("kernel_texels"), 3);
  EXPECT_EQ(values.choice("pattern"), "grid");
  values.set("kernel_texels=9");
  values.set("pattern=poisson");
  values.set("bias_slope_texels=2.5");
  values.set("caster_faces=back");
  EXPECT_EQ(values.getInt("kernel_texels"), 9);
  EXPECT_EQ(values.choice("pattern"), "poisson");
  EXPECT_DOUBLE_EQ(values.get("bias_slope_texels"), 2.5);
  EXPECT_EQ(values.choice("caster_faces"), "back");
  // shadow_map_size: auto by default (the frame chooses), a number, then auto again.
  EXPECT_TRUE(values.automatic("shadow_map_size"));
  values.set("shadow_map_size=512");
  EXPECT_FALSE(values.automatic("shadow_map_size"));
  EXPECT_EQ(values.getInt("shadow_map_size"), 512);
  values.set("shadow_map_size=auto");
  EXPECT_TRUE(values.automatic("shadow_map_size"));
  EXPECT_FALSE(values.automatic("kernel_texels"));
}

TEST(ParameterValues, BadAssignmentsNameTheKeyAndValue)
{
  ParameterValues values = findTechnique("pcf").defaultParameters();
  struct Case
  {
    std::string assignment;
    std::vector<std::string> mustMention;
  };
  const Case cases[] = {
    { "radius=3", { "radius", "pcf", "kernel_texels" } },        // unknown, lists the known ones
    { "kernel_texels=0", { "kernel_texels", "0", "1", "64" } },    // below range
    { "kernel_texels=65", { "kernel_texels", "65" } },             // above range
    { "kernel_texels=2.5", { "kernel_texels", "integer" } },       // not an integer
    { "kernel_texels=nan", { "kernel_texels" } },                  // NaN
    { "kernel_texels=inf", { "kernel_texels" } },                  // infinity
    { "kernel_texels=three", { "three", "not a number" } },
    { "pattern=spiral", { "spiral", "grid", "poisson" } },         // not a choice
    { "kernel_texels", { "key=value" } },                          // no '='
    { "=3", { "key=value" } },
    { "bias_constant_texels=-1", { "bias_constant_texels", "-1" } },
    { "shadow_map_size=0", { "shadow_map_size", "16", "8192", "or auto" } }, // auto is the word, not 0
    { "shadow_map_size=big", { "big", "not a number nor auto" } },
  };
  for (const Case& c : cases)
  {
    const std::string message = inputErrorMessage([&] { values.set(c.assignment); });
    for (const std::string& word : c.mustMention)
    {
      EXPECT_NE(message.find(word), std::string::npos) << "'" << c.assignment << "' -> " << message;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
  // Nothing was changed by the rejected assignments.
  EXPECT_EQ(values.getInt("kernel_texels"), 3);
  EXPECT_EQ(values.choice("pattern"), "grid");
}

// Typed settings (core/Parameters.h): each choice maps to its enumerator by name, not by its position in the spec,
// and a choice the settings leave unpaired stops at once rather than reading as another enumerator.
TEST(TypedSettings, ChoicesMapToTheirEnumeratorsByName)
{
  enum class Shape
  {
    Disk,
    Square,
    Hexagon
  };
  const std::vector<ParameterSpec> specs = {
    { "shape", 1, 0, 2, "", "a test enumeration", { "square", "disk", "hexagon" }, true },
  };
  ParameterValues values("test", specs);
  const auto shape = [&values] {
    return choiceOf<Shape>(
      values, "shape", { { "disk", Shape::Disk }, { "square", Shape::Square }, { "hexagon", Shape::Hexagon } });
  };
  EXPECT_EQ(shape(), Shape::Disk) << "the default: choice 1 of the spec, disk";
  values.set("shape=square");
  EXPECT_EQ(shape(), Shape::Square);
  values.set("shape=hexagon");
  EXPECT_EQ(shape(), Shape::Hexagon);
  EXPECT_DEATH(choiceOf<Shape>(values, "shape", { { "disk", Shape::Disk }, { "square", Shape::Square } }),
    "choice 'hexagon' of 'shape'");
}

// pcf's typed settings hold what `--set` assigned, and its light-space request hands the shadow map the kernel width
// (the focus margin), not the name of a parameter.
TEST(TypedSettings, PcfSettingsFollowTheParameters)
{
  const TechniqueDescriptor& pcf = findTechnique("pcf");
  ParameterValues values = pcf.defaultParameters();
  PcfSettings settings = PcfSettings::from(values);
  EXPECT_EQ(settings.kernelTexels, 3);
  EXPECT_EQ(settings.pattern, PcfPattern::Grid);
  EXPECT_EQ(settings.poissonSamples, 16);
  EXPECT_EQ(settings.filter, PcfFilter::Nearest);
  EXPECT_DOUBLE_EQ(settings.bias.constantTexels, 0.5);
  values.set("kernel_texels=9");
  values.set("pattern=poisson");
  values.set("poisson_samples=24");
  values.set("filter=hardware_bilinear");
  values.set("bias_slope_texels=2.5");
  settings = PcfSettings::from(values);
  EXPECT_EQ(settings.kernelTexels, 9);
  EXPECT_EQ(settings.pattern, PcfPattern::Poisson);
  EXPECT_EQ(settings.poissonSamples, 24);
  EXPECT_EQ(settings.filter, PcfFilter::HardwareBilinear);
  EXPECT_DOUBLE_EQ(settings.bias.slopeTexels, 2.5);
  const LightSpaceRequest request = pcf.lightSpaceRequestFor(values);
  EXPECT_EQ(request.filterParameter, "kernel_texels");
  EXPECT_EQ(request.filterTexels, 9.0);
  EXPECT_EQ(request.momentExponent, 0.0);
  EXPECT_EQ(findTechnique("hard").lightSpaceRequestFor(findTechnique("hard").defaultParameters()).filterParameter, "")
    << "hard filters nothing";
}

TEST(PoissonDisk, PointsAreInTheUnitDiskAndWellSeparated)
{
  const auto& disk = poissonDisk();
  ASSERT_EQ(static_cast<int>(disk.size()), maxPoissonSamples);
  double closest = 1e300;
  for (std::size_t i = 0; i < disk.size(); ++i)
  {
    EXPECT_LE(glm::length(disk[i]), 1.0) << i;
    for (std::size_t j = 0; j < i; ++j)
    {
      closest = std::min(closest, glm::length(disk[i] - disk[j]));
    }
  }
  // 64 points in a unit disk: a blue-noise set keeps them apart; uniform random would have pairs far
  // closer than this (expected nearest pair ~0.02).
  EXPECT_GT(closest, 0.12) << "closest pair distance";
  // The first 16 (the default count) already cover the disk: some point in each quadrant, far out.
  int quadrants[4] = { 0, 0, 0, 0 };
  for (int i = 0; i < 16; ++i)
  {
    quadrants[(disk[i].x > 0 ? 1 : 0) + (disk[i].y > 0 ? 2 : 0)]++;
  }
  for (int q = 0; q < 4; ++q)
  {
    EXPECT_GE(quadrants[q], 2) << "quadrant " << q;
  }
}

TEST(PixelHash, IsDeterministicAndSpreadsAngles)
{
  EXPECT_EQ(pixelHash(3, 7), pixelHash(3, 7));
  EXPECT_NE(pixelHash(3, 7), pixelHash(7, 3));
  // Angles of a 32x32 block cover [0, 2 pi) roughly uniformly (8 bins, each 128 +- 40).
  int bins[8] = {};
  for (std::uint32_t y = 0; y < 32; ++y)
  {
    for (std::uint32_t x = 0; x < 32; ++x)
    {
      const double angle = pixelHashAngle(x, y);
      ASSERT_GE(angle, 0.0);
      ASSERT_LT(angle, 6.283185307179586);
      bins[static_cast<int>(angle / 6.283185307179586 * 8)]++;
    }
  }
  for (int bin : bins)
  {
    EXPECT_NEAR(bin, 128, 40);
  }
}

} // namespace
} // namespace sl
