// When no EGL display can give an OpenGL 4.5 core context, shadowlab fails with one line that says what
// it tried, a nonzero exit, and no output directory. Forcing the EGL device platform on a machine with no
// hardware EGL device (CI, llvmpipe) exercises exactly that path.
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

namespace sl
{
namespace
{

using test::ProcessRun;
using test::runShadowlab;

bool hasHardwareEglDevice()
{
  // The same forced run succeeds on a machine with a GPU; then this test has nothing to show.
  return std::getenv("SHADOWLAB_TEST_HAS_EGL_DEVICE") != nullptr;
}

TEST(GraphicsErrors, NoUsableEglDisplayIsOneLineNamingWhatWasTried)
{
  ASSERT_FALSE(hasHardwareEglDevice()) << "run this test where only Mesa's software EGL exists (CI)";
  const std::filesystem::path out = test::testOutputDir() / "graphics-error-out";
  std::filesystem::remove_all(out);
  const ProcessRun run = runShadowlab("render " + test::datasetPath("planar-occluder").string() +
      " --technique hard --resolution 32x32 --out " + out.string(), "SHADOWLAB_EGL=device");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_EQ(std::count(run.standardError.begin(), run.standardError.end(), '\n'), 1) << run.standardError;
  EXPECT_NE(run.standardError.find("EGL"), std::string::npos) << run.standardError;
  EXPECT_NE(run.standardError.find("device"), std::string::npos) << run.standardError;
  EXPECT_FALSE(std::filesystem::exists(out)) << "no output on failure";
}

TEST(GraphicsErrors, UnknownEglPlatformNameIsRejected)
{
  const ProcessRun run = runShadowlab("render " + test::datasetPath("planar-occluder").string() +
      " --technique hard --resolution 32x32 --out " + (test::testOutputDir() / "graphics-error-out2").string(),
    "SHADOWLAB_EGL=wayland");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.standardError.find("SHADOWLAB_EGL='wayland'"), std::string::npos) << run.standardError;
}

TEST(GraphicsErrors, SurfacelessMesaWorksAndPrintsNoFalseGlewError)
{
  const std::filesystem::path out = test::testOutputDir() / "graphics-surfaceless-out";
  const ProcessRun run = runShadowlab("render " + test::datasetPath("planar-occluder").string() +
      " --technique hard --resolution 32x32 --out " + out.string(), "SHADOWLAB_EGL=surfaceless");
  EXPECT_EQ(run.exitCode, 0) << run.standardError;
  EXPECT_EQ(run.standardError.find("GLEW"), std::string::npos) << run.standardError;
  EXPECT_TRUE(std::filesystem::exists(out / "stats.json"));
}

} // namespace
} // namespace sl
