// When no EGL display can give an OpenGL 4.5 core context, shadowlab fails with one line that says what
// it tried, a nonzero exit, and no output directory. Forcing the EGL device platform on a machine with no
// hardware EGL device (CI, llvmpipe) exercises exactly that path.
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace sl
{
namespace
{

using test::RunResult;

// A small render of planar-occluder to `out` with SHADOWLAB_EGL=`eglPlatform` in the environment.
RunResult renderWithEglPlatform(const std::string& eglPlatform, const std::filesystem::path& out)
{
  const test::TempDir workDir;
  return test::runShadowlabIn({ "render", test::datasetPath("planar-occluder").string(), "--technique", "hard",
                                "--resolution", "32x32", "--out", out.string() },
    workDir.path(), "export SHADOWLAB_EGL=" + test::shellQuote(eglPlatform));
}

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
  const RunResult run = renderWithEglPlatform("device", out);
  EXPECT_NE(run.exitCode, 0);
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find("EGL"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("device"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out)) << "no output on failure";
}

TEST(GraphicsErrors, UnknownEglPlatformNameIsRejected)
{
  const RunResult run = renderWithEglPlatform("wayland", test::testOutputDir() / "graphics-error-out2");
  EXPECT_NE(run.exitCode, 0);
  EXPECT_NE(run.err.find("SHADOWLAB_EGL='wayland'"), std::string::npos) << run.err;
}

TEST(GraphicsErrors, SurfacelessMesaWorksAndPrintsNoFalseGlewError)
{
  const std::filesystem::path out = test::testOutputDir() / "graphics-surfaceless-out";
  const RunResult run = renderWithEglPlatform("surfaceless", out);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err.find("GLEW"), std::string::npos) << run.err;
  EXPECT_TRUE(std::filesystem::exists(out / "stats.json"));
}

} // namespace
} // namespace sl
