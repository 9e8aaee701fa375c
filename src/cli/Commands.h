// The shadowlab subcommands. Each returns the process exit code; user errors are thrown as InputError
// and reported once by main().
#pragma once

#include "io/OutputDirectory.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace sl
{

struct FrameResult;
struct TechniqueDescriptor;

// What `render` and `probe` both take: one scene, one technique, one frame, one output directory.
struct FrameCommandOptions
{
  std::string sceneFile;
  std::vector<std::string> sceneOverrides; // "/json/pointer=value" (--scene-set)
  std::string technique = "pcf";
  std::vector<std::string> settings;
  std::string resolution; // "WxH" or empty
  std::string outDir;
  int lightIndex = 0;
  bool force = false; // --force (OutputDirectory.h)
  bool quiet = false;
};

struct RenderOptions : FrameCommandOptions
{
  RenderOptions() { outDir = "shadowlab-render"; }
  bool progress = false; // --progress: a long frame's estimate even with --quiet (cli/CommandProgress.h)
};

int runRender(const RenderOptions& options, std::ostream& log);

// shadowlab list [TECHNIQUE...]: every technique, or only those named (each argument one name or a comma list).
struct ListOptions
{
  std::vector<std::string> techniques; // empty: all
  bool json = false;
  bool structures = false; // --structures: the light-space structures and the techniques that use each
};
int runList(const ListOptions& options, std::ostream& out);

struct ReferenceOptions
{
  std::string sceneFile;
  std::vector<std::string> sceneOverrides;
  int samples = 1024;         // --reference-samples (old spelling --samples)
  bool samplesGiven = false;  // it was on the command line (with --light-samples, N defaults to 16)
  std::string samplesOption = "--reference-samples"; // the spelling the user typed, as errors name it
  std::string sampling = "stratified";
  std::string lightSamples;   // --light-samples PATTERN (lightSamplePatternNames()); "" = `sampling`
  bool lightSamplesGiven = false; // --light-samples was on the command line (an empty PATTERN is refused)
  int msaa = 1;               // --msaa 1 | 4: trace every sample position of a 4x multisampled G-buffer, average
  std::uint64_t seed = 1;
  std::string resolution; // "WxH" or empty
  std::string outDir = "shadowlab-reference";
  int lightIndex = 0;
  int threads = 0; // 0: all cores
  bool force = false; // --force (OutputDirectory.h)
  bool quiet = false;
  bool progress = false; // --progress (cli/CommandProgress.h)
  std::string tile;      // --tile K/N: trace only row tile K of N (cli/ReferenceTiles.h); "" = every row
};
int runReference(const ReferenceOptions& options, std::ostream& log);

// shadowlab reference-merge TILE... --out DIR: the row tiles of one reference (reference --tile K/N, every K once)
// into the buffers.vti the single-process reference writes, bit for bit (cli/ReferenceTiles.h).
struct ReferenceMergeOptions
{
  std::vector<std::string> tileDirs;
  std::string outDir = "shadowlab-reference";
  bool force = false;
  bool quiet = false;
};
int runReferenceMerge(const ReferenceMergeOptions& options, std::ostream& log);

struct CompareOptions
{
  std::string testFile;
  std::string referenceFile;
  std::string array = "visibility";
  std::string outDir = "shadowlab-compare";
  bool force = false; // --force (OutputDirectory.h)
  bool quiet = false;
};
int runCompare(const CompareOptions& options, std::ostream& log);

struct BenchOptions
{
  std::vector<std::string> sceneFiles;
  std::string techniques = "hard,pcf";         // comma-separated (-t/--technique, old spelling --techniques)
  std::vector<std::string> sweeps;             // "key=v1,v2,..." (several: all combinations)
  std::vector<std::string> settings;           // "key=value" for every configuration that has the key
  std::vector<std::string> sceneOverrides;     // "/json/pointer=value" applied to every scene
  std::vector<std::string> sceneSweeps;        // "/json/pointer=v1,v2,..." (several: all combinations)
  int repeat = 5;                              // timed frames after one warm-up frame
  std::string resolution = "256x256";          // WxH, or a comma list: every configuration at every size
  int referenceSamples = 1024;                 // --reference-samples (old spelling --samples)
  std::string referenceSamplesOption = "--reference-samples"; // the spelling the user typed, as errors name it
  std::string cacheDir = ".shadowlab-cache";   // ray-traced references, keyed by scene + resolution + samples
  std::string outDir = "shadowlab-bench";
  bool force = false; // --force (OutputDirectory.h)
  bool quiet = false;
  bool progress = false; // --progress (cli/CommandProgress.h)
  // --depth-profile BUFFER: each configuration's BUFFER binned over the eye's depth (metrics/DepthProfile.h) into
  // depth_profile.csv and depth_profile_<scene>.png; --depth-bins, --depth-range "near,far" ("" = the pixels' own).
  std::string depthProfile;
  int depthBins = 16;
  std::string depthRange;
  // --view-stats B1,B2,...: each configuration's largest, 99th-percentile and mean value of each one-component buffer
  // over the view (bench-run's view_stats) as bench.csv columns <B>_max, <B>_p99, <B>_mean, and, against the first
  // --sweep key, the charts view_<B>_<scene>.png and sweep_above_0.05_<scene>.png.
  std::string viewStats;
  // --plan DIR: write the bench as jobs instead of running it; --collect DIR: merge what a plan's tasks wrote
  // (cli/BenchPlan.h). The --slurm-* values go into the plan's batch script.
  std::string planDir;
  std::string collectDir;
  std::string slurmPartition;
  std::string slurmTime;
  int slurmGpus = 0;
  int slurmThrottle = 0;
  int referenceTiles = 1; // row tiles per reference in a plan (reference --tile K/N, then reference-merge)
  // --baseline DIR: an earlier bench's output; summary.md compares this run's errors with its rows
  // (cli/BenchBaseline.h), bench.csv gains baseline_rmse and rmse_delta.
  std::string baselineDir;
};
int runBench(const BenchOptions& options, std::ostream& log);

// One configuration, run by `bench` in a child process (hidden subcommand `bench-run`): a warm-up frame
// and `repeat` timed frames, medians, and the error against the reference; the result is JSON in `resultFile`.
struct BenchRunOptions
{
  std::string sceneFile;
  std::vector<std::string> sceneOverrides;
  std::string technique;
  std::vector<std::string> settings;
  std::string resolution;
  int repeat = 5;
  std::string referenceFile; // buffers.vti of the reference; empty: no error metrics
  std::string resultFile;
  std::string depthProfile;  // as BenchOptions: the result gains "depth_profile" (metrics/DepthProfile.h)
  int depthBins = 16;
  std::string depthRange;
  std::string viewStats;     // as BenchOptions: the result gains "view_stats"
};
int runBenchConfiguration(const BenchRunOptions& options);

// shadowlab probe: one pixel replayed on the technique's CPU twin with a recorder (src/probe/Probe.h).
struct ProbeOptions : FrameCommandOptions
{
  ProbeOptions() { outDir = "shadowlab-probe"; }
  std::string pixel; // "X,Y", image coordinates, row 0 at the bottom
  std::string pick;  // "x,y,z" or "world x,y,z" (main joins `--pick world X,Y,Z` into one value)
};
// Exit 0 when the twin agrees with the GPU buffer (or the pixel is ambiguous: within float rounding of a
// decision), 3 when they differ beyond the tests' tolerance (the probe's files are still written).
int runProbe(const ProbeOptions& options, std::ostream& log);

// shadowlab view: a desktop window on the offscreen pipeline's frames (cli/ViewerWindow.h,
// docs/tools.md, "The viewer").
struct ViewOptions
{
  std::string sceneFile;
  std::vector<std::string> sceneOverrides;
  std::string technique = "pcf";
  std::vector<std::string> settings;
  std::string resolution;
  int lightIndex = 0;
  std::string recordFile;            // --record: the session's events (vtkInteractorEventRecorder)
  std::string playFile;              // --play: replay these events, then exit
  std::string screenshotDir = ".";   // where the s key writes view-NNN-<technique>-<buffer>.png
  bool force = false;                // --force: --record may replace an existing file that is not a recording
};
// Exit 2 with one line when there is no display (no DISPLAY, XOpenDisplay fails, no GLX), before any window or
// frame. Every action of the session prints one line on `out`.
int runView(const ViewOptions& options, std::ostream& out);

// shadowlab montage: one buffer of several run directories side by side on one colour scale (vis/Montage.h).
struct MontageCommandOptions
{
  std::vector<std::string> runDirs; // output directories of render / reference (buffers.vti + stats.json)
  std::string buffer;
  std::string outFile = "shadowlab-montage.png";
  std::string referenceDir; // a run whose visibility the others' error labels are measured against ("" = none)
  bool quiet = false;
  bool force = false; // --out may replace an existing file montage did not write (never an input)
};
int runMontage(const MontageCommandOptions& options, std::ostream& log);

// shadowlab lessons: the lesson pages generated from real runs (src/lessons/).
struct LessonsOptions
{
  std::string outDir = "shadowlab-lessons"; // docs/lessons only when asked (--out docs/lessons)
  std::string resolution = "256x256";
  std::vector<std::string> only; // lesson names; empty = every lesson
  bool list = false;             // --list: the lessons' names and titles, nothing run or written
  bool force = false;            // --force (OutputDirectory.h)
  bool quiet = false;
  bool progress = false;         // --progress (cli/CommandProgress.h)
};
int runLessons(const LessonsOptions& options, std::ostream& log);

// shadowlab differential: every technique and choice against the ray tracer on random scenes (issue 27;
// differential/Differential.h). Exit 4 when a configuration failed (its line names the seed and the command).
struct DifferentialCommandOptions
{
  std::string seeds = "1..4";   // "A..B" or "A,B,..."
  std::string techniques;       // comma-separated; empty: all
  std::string choice;           // "default" or key=value; empty: every enumerated choice
  int maxSide = 128;
  int samples = 256;            // reference samples per pixel (--reference-samples, old spelling --samples)
  std::string samplesOption = "--reference-samples"; // the spelling the user typed, as errors name it
  std::filesystem::path outDir = "shadowlab-differential";
  bool force = false;
  bool quiet = false;
  bool progress = false; // --progress (cli/CommandProgress.h)
};
int runDifferential(const DifferentialCommandOptions& options, std::ostream& log);

// One line when some pixels of `frame` are marked by the technique's declared approximations (the buffer
// `approximation`), naming the count and the approximations. Returns how many.
std::size_t reportApproximatePixels(const FrameResult& frame, std::ostream& log);

// The request `render` and `probe` make from what the user typed, checked (technique known, every --set valid,
// --resolution well formed) before anything touches the GPU or the disk.
RenderRequest checkedRenderRequest(const std::string& technique, const std::vector<std::string>& settings,
  int lightIndex, const std::string& resolution);

// `render`'s and `probe`'s checks before the GPU or the disk is touched: the request (checkedRenderRequest), the
// scene with its --scene-set values, and --out against every input (the scene's files, the technique's file
// parameters) for `command`'s output contract (OutputDirectory.h).
struct CheckedFrameCommand
{
  RenderRequest request;
  Scene scene;
  OutputTarget output;
};
CheckedFrameCommand checkFrameCommand(const FrameCommandOptions& options, const std::string& command);

// "WxH" -> size, each side 1 .. kMaxImageSide; throws InputError naming --resolution.
glm::ivec2 parseResolution(const std::string& text);

// Every --set assignment valid for `technique` (known key, value in range) and no key given twice; throws
// InputError naming the assignment.
void checkSettings(const TechniqueDescriptor& technique, const std::vector<std::string>& settings);

// Every --scene-set pointer given once, and every --scene-sweep pointer once and not also by --scene-set (the
// later value would silently win, as a repeated --set key would); throws InputError naming the pointer.
void checkSceneOverrides(const std::vector<std::string>& overrides, const std::vector<std::string>& sweeps = {});

// One warning line per object whose mesh had degenerate triangles (dropped by the loader); returns their sum.
std::size_t reportDroppedTriangles(const Scene& scene, const std::string& sceneFile, std::ostream& log);
// One warning line when some pixels of `frame` were cut short (a GL's loop cap, a budget): their values are
// not exact. Returns how many.
std::size_t reportCutShortPixels(const FrameResult& frame, std::ostream& log);
// One warning line per technique buffer that flags pixels of `frame` (BufferSpec::flagAtOrAbove): how many, the
// buffer and its threshold, and the buffer's warning. Returns how many pixels in all.
std::size_t reportFlaggedPixels(const FrameResult& frame, std::ostream& log);

// The files a command reads for a scene (the scene file, its meshes and alpha textures): --out must not hold them.
std::vector<std::filesystem::path> sceneInputs(const Scene& scene, const std::string& sceneFile);
// The files `settings` name through `technique`'s file parameters (ParameterSpec::file, e.g. ss08's
// budget_image): inputs too, whichever the technique. `settings` must be valid (checkSettings).
std::vector<std::filesystem::path> fileParameterInputs(const TechniqueDescriptor& technique,
  const std::vector<std::string>& settings);

} // namespace sl
