// Shared helpers for ShadowLab's tests: datasets by name, one renderer per test process, and the
// read-back buffers of a frame as CPU-reference inputs.
#pragma once

#include "pipeline/ShadowRenderer.h"
#include "support/CliRun.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"
#include "techniques/ShadowMapReference.h"

#include <gtest/gtest.h>
#include <nlohmann/json_fwd.hpp>

#include <array>
#include <filesystem>
#include <functional>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace sl::test
{

inline constexpr double kPi = 3.14159265358979323846;
// A uniform draw in [low, high).
inline double uniform(std::mt19937_64& random, double low, double high)
{
  return std::uniform_real_distribution<double>(low, high)(random);
}
// The buffer `name` of a rendered frame; throws when the frame has none.
const ImageF& bufferOf(const FrameResult& frame, const std::string& name);
// The array `name` among a written file's arrays (readVti); throws when there is none.
const NamedImage& arrayNamed(const std::vector<NamedImage>& arrays, const std::string& name);
// A JSON file (stats.json, probe.json), parsed.
nlohmann::json readJson(const std::filesystem::path& path);
// A scene from the JSON texts of its camera, its one light and its objects (a comma-separated list).
Scene sceneFromJson(const std::string& camera, const std::string& light, const std::string& objects);
// A 6 x 6 ground quad at y = 0 facing up, as a scene object's JSON.
inline constexpr const char* kGroundQuadJson =
  R"({ "primitive": "quad", "size": [6, 6], "normal": [0, 1, 0], "up": [0, 0, -1] })";
// The pixel (x, y) of a three-component buffer (position, normal).
inline glm::dvec3 vec3At(const ImageF& image, int x, int y)
{
  return { image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2) };
}

std::filesystem::path sourceDir();           // the repository root
std::filesystem::path testOutputDir();        // <build>/test-output, created on demand
// A perforated plate's alpha mask like fence-meshed's: 20 x 20 texels with 16 square holes of 2 x 2 texels (4 x 4 of
// them), written as a PNG named `fileName` into the test output; mesh_alpha meshes it as 672 triangles.
std::string sixteenHoleMaskPng(const std::string& fileName);
std::filesystem::path datasetPath(const std::string& name); // datasets/<name>/scene.json
// <test-output>/<name>, removed if it exists (a test's absolute output path).
std::filesystem::path freshOutputDir(const std::string& name);
// shadowlab with `arguments` in a fresh temporary working directory (runShadowlabIn, CliRun.h).
RunResult runShadowlabInTempDir(const std::vector<std::string>& arguments);
// Overrides of stacked-occluders that put its upper occluder 1 below a light of size 2 (issue 13): at the default
// 1024^2 map the contour kernels reach ~500 texels, past what a brute force finishes under llvmpipe's loop cap.
std::vector<std::string> wideKernelOverrides();
// `overrides` as shadowlab arguments: --scene-set pointer=value for each.
std::vector<std::string> sceneSetArguments(const std::vector<std::string>& overrides);
// Overrides of stacked-occluders (issue 13): its occluders replaced by parallel rectangles {x, y, z, width,
// depth} (horizontal quads, objects 1..), under its square light moved to `lightHeight` with side `lightSize`.
std::vector<std::string> stackedRectangles(const std::vector<std::array<double, 5>>& rectangles, double lightHeight,
  double lightSize);
// A seeded random stack of `count` such rectangles: light 3-5 high and 1-3 wide, the highest rectangle 0.6-1.2
// below it, the others anywhere from 0.3 up to 1.2 below the light; sizes 0.3-1.5, centres within 0.8 of the
// axis. Draws from `generator` in a fixed order, so a seed gives one scene.
std::vector<std::string> randomRectangleStack(std::mt19937& generator, int count);
// Overrides of near-light: a small caster 0.15 below the light, outside the focus stage's first window but
// inside the widened one (LightView.cpp), moves the map's near plane to 0.15, so the kernels around it are
// clamped by the map's border.
std::vector<std::string> borderClampedKernelOverrides();
Scene loadDataset(const std::string& name);
// An object from a triangle list (3 corners each) with split vertices and flat normals (the G-buffer needs normals),
// for scenes built in code (object-space techniques: open, non-manifold, degenerate casters).
SceneObject flatObject(const std::string& name, const std::vector<glm::dvec3>& corners);
// Appends the four faces of the tetrahedron `vertices` to `corners`, each wound outward (for flatObject).
void appendTetrahedron(std::vector<glm::dvec3>& corners, const std::array<glm::dvec3, 4>& vertices);
// Every datasets/*/scene.json with shadows to compare: all but facing-tiles, the survey's Fig. 12 as a scene, whose
// tiles shadow nothing (every technique's image is the same there; tests/render/WarpFig12Test.cpp measures it).
std::vector<std::string> datasetNames();
// The techniques that render `wall-ring`: its point light has visible receivers all around it, which one shadow map
// cannot cover: the object-space ones and those with cube shadow maps (cube_map, survey §2); every other technique
// that takes point lights refuses it by design. tests/cli/SamplingDatasetsCliTest.cpp checks that each of those
// refuses it, so this list cannot go stale.
const std::vector<std::string>& wallRingTechniques();
// Whether `technique` renders `dataset` (every pair but wall-ring with a technique outside wallRingTechniques()):
// the sweeps over every dataset (datasetTechniquePairs, the focus and comparator checks) leave the refusals out.
bool rendersDataset(const std::string& technique, const std::string& dataset);

// One case of the suites that run every registered technique on every dataset (the regression baselines, the
// NaN/inf sweep): one gtest, hence one ctest case, per pair, so `ctest -j` spreads them.
struct DatasetTechnique
{
  std::string dataset;
  std::string technique;
};
// gtest prints a failing case's parameter with this instead of a byte dump.
void PrintTo(const DatasetTechnique& pair, std::ostream* os);
// Every dataset x every registered technique that supports the dataset's shadow-casting light (light 0), so a
// newly registered technique or dataset gets its cases without a change here. A dataset that does not load is
// kept for every technique, so its cases fail with the loader's message.
std::vector<DatasetTechnique> datasetTechniquePairs();
// The datasets of datasetTechniquePairs() that `technique` renders, in its order (cheap: no mesh is loaded, so it
// can pick a parameterised suite's cases at registration).
std::vector<std::string> datasetsRenderedBy(const std::string& technique);
// The gtest name of a case: "<dataset>_<technique>" with every character that is not a letter or digit turned
// into '_' (planar-occluder/pcf -> planar_occluder_pcf).
std::string datasetTechniqueName(const testing::TestParamInfo<DatasetTechnique>& info);

// The stacked-occluders geometry under a light given as JSON (e.g. a directional or spot light), for the
// light types no dataset uses.
Scene stackedOccludersUnder(const std::string& lightJson);

// Closed form for a square light of side `lightSize` at height `lightHeight` over the ground (y = 0), facing
// down, and a parallel square occluder of side `occluderSize` at `occluderHeight`, both centred over the
// origin with edges along x and z: the visible fraction of the light from ground point (x, z) is one minus
// the overlap of the light square with the occluder's projection through the point onto the light plane,
// the occluder scaled by lightHeight / occluderHeight about the point.
double parallelSquaresVisibility(
  double lightSize, double lightHeight, double occluderSize, double occluderHeight, double x, double z);

// RMSE of a frame's visibility against a closed form over the ground pixels (covered, y = 0), with the
// number of ground pixels and of those strictly inside the exact penumbra (0 < exact < 1).
struct GroundError
{
  double rmse = 0.0;
  double penumbraRmse = 0.0;
  double maxError = 0.0;
  int ground = 0;
  int penumbra = 0;
};
GroundError groundErrorAgainst(const FrameResult& frame, const std::function<double(double x, double z)>& exact);

// The test process's one renderer (its EGL context and VTK window), for tests that drive it themselves.
ShadowRenderer& sharedRenderer();

// Renders with one renderer per test process (its EGL context and VTK window are the slow part on llvmpipe).
FrameResult renderDataset(const Scene& scene, const std::string& technique, int width, int height,
  const std::vector<std::string>& settings = {});

// ss08 with the settings its older tests were written for, its defaults until issue 27: micropatches accumulated by
// area (the defaults are now microrects with occlusion bitmasks, docs/bench/ss08-defaults). `settings` override them.
FrameResult renderSs08(const Scene& scene, int width, int height, const std::vector<std::string>& settings = {});

// The reference's multisample mode on the shared renderer: one G-buffer-only frame per sample position
// (ShadowRenderer::renderSampleGBuffers).
std::vector<FrameResult> renderSampleGBuffers(const Scene& scene, int width, int height, int samples);

// The shared renderer's window, for tests that run a pass outside a frame (tests/render/MicrorectGpuTest.cpp).
// Use it rather than a second EGL context: each context terminates the process's EGL display when it goes, which
// breaks the other one's teardown.
vtkSLEglRenderWindow* sharedRenderWindow();

// "dataset setting setting ..." for failure messages and [ measured ] lines.
std::string caseLabel(const std::string& dataset, const std::vector<std::string>& settings);

// Adds a gtest failure, naming `label` and the buffer, for every non-finite value in any buffer or light-space array
// of `frame` and for a visibility outside [0, 1] (the NaN/inf sweep's check; the regression suite applies it to its
// default frames, the sweep to the variants).
void expectFiniteBuffersAndVisibilityInRange(const FrameResult& frame, const std::string& label);

// Adds a gtest failure, naming `where` and the buffer, for every buffer of `actual` that is not `expected`'s bit for
// bit (a structure built differently must leave the frame unchanged: prefilter_region, reuse).
void expectBuffersBitIdentical(const FrameResult& actual, const FrameResult& expected, const std::string& where);
// Light-space array `name` of a frame that built it only where `builtMask` is not 0, against `whole`'s (built
// everywhere): a gtest failure naming `where` when a built texel differs in any bit or an unbuilt one is not 0.
void expectBuiltTexelsOfWhole(
  const FrameResult& actual, const FrameResult& whole, const std::string& name, const ImageF& builtMask, const std::string& where);
// Of the shadow-tested pixels of `frame`, how many read a texel `builtMask` marks 0: each pixel's texel is the one
// holding its projection into the frame's light view (the CPU's double-precision projection, clamped to the map, as a
// prefiltered lookup reads it). `lookups` receives the number of shadow-tested pixels.
int unbuiltLookupTexels(const FrameResult& frame, const ImageF& builtMask, int& lookups);

// A light-space array of a frame by name (throws when the frame has none of that name).
const ImageF& lightSpaceArray(const FrameResult& frame, const std::string& name);
// The float summed-area table as stored (2 components, centred z and z^2), from sat_z and sat_z2.
ImageF floatSummedAreaTable(const FrameResult& frame);

// The read-back inputs a CPU reference of a shadow-map technique needs, from a rendered frame.
ShadowMapInputs shadowMapInputs(const FrameResult& frame, const Scene& scene, int lightIndex = 0);

// The same frame's receivers as inputs of the ray-traced reference (Embree) for the scene's light.
ReferenceInputs referenceInputs(const FrameResult& frame, const Scene& scene, int lightIndex = 0);

} // namespace sl::test
