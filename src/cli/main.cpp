// shadowlab: render scenes with published real-time shadow algorithms and export their internals.
// Run `shadowlab --help` or `shadowlab <command> --help`.
#include "cli/Commands.h"
#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "io/vtkSLOutputWindow.h"
#include "lightspace/LightSampleSet.h"

#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <vector>

namespace
{

// Adds the --force flag every command that writes an output directory has (see OutputDirectory.h).
void addForceFlag(CLI::App* command, bool& force)
{
  command->add_flag("--force", force,
    "Replace --out even when it is a non-empty directory that shadowlab did not write (never the current "
    "directory, an ancestor of it, the home directory, or a directory holding an input)");
}

// "grid | stratified | ...": the choices of --light-samples, from the list the parser checks against.
std::string joinedLightSamplePatterns()
{
  std::string names;
  for (const std::string& name : sl::lightSamplePatternNames())
  {
    names += (names.empty() ? "" : " | ") + name;
  }
  return names;
}

// --seed: a decimal integer in 0 .. 2^64-1, checked on the text before CLI11 converts it (its conversion
// saturates a larger value, and CLI::NonNegativeNumber names its bound as a 309-digit DBL_MAX).
CLI::Validator seedRange()
{
  return CLI::Validator(
    [](std::string& text) -> std::string {
      const std::string max = std::to_string(std::numeric_limits<std::uint64_t>::max());
      const bool digits = !text.empty() && text.size() <= max.size() &&
        text.find_first_not_of("0123456789") == std::string::npos;
      const bool inRange = digits && (text.size() < max.size() || text <= max);
      return inRange ? std::string() : sl::printable(text) + ": expected an integer in 0 .. " + max;
    },
    "0 .. 2^64-1");
}

// An option renamed in this release (issue 31, "one command line"): the old spelling still works for one release,
// hidden from --help, and a run that uses it prints one note on stderr; giving both spellings is an error.
struct RenamedOption
{
  CLI::Option* old = nullptr;
  CLI::Option* replacement = nullptr;
  std::string oldName;     // "--techniques" (CLI11 gives a hidden option no name)
  std::string newSpelling; // "-t/--technique"
};

// One subcommand: the CLI11 command its options were added to, its renamed options, and what runs when it was
// parsed. The options it fills live in main, beside it.
struct Command
{
  CLI::App* command = nullptr;
  std::function<int()> run;
  std::vector<RenamedOption> renamed;
};

// `oldName` (e.g. "--samples"), hidden, filling `variable` as `replacement` does.
template <typename T>
RenamedOption addOldSpelling(CLI::App* command, const std::string& oldName, T& variable, CLI::Option* replacement,
  const std::string& newSpelling)
{
  CLI::Option* old = command->add_option(oldName, variable)->group("");
  return { old, replacement, oldName, newSpelling };
}

// Several techniques: -t a,b or -t a -t b (joined into one comma list, as the commands split it).
std::string joinedTechniqueList(const std::vector<std::string>& items)
{
  std::string joined;
  for (const std::string& item : items)
  {
    joined += (joined.empty() ? "" : ",") + item;
  }
  return joined;
}

// --progress: progress lines with the elapsed time and an estimate even when stderr is not a terminal
// (cli/CommandProgress.h).
void addProgressFlag(CLI::App* command, bool& progress)
{
  command->add_flag("--progress", progress,
    "Progress lines (elapsed, time left) on stderr even when it is not a terminal, and with --quiet; by default "
    "they appear only on a terminal");
}

Command addRenderCommand(CLI::App& app, sl::RenderOptions& render)
{
  CLI::App* renderCommand = app.add_subcommand("render", "Render a scene with one technique into an output directory");
  renderCommand->add_option("scene", render.sceneFile, "Scene file (JSON, see docs/scene-format.md)")->required();
  renderCommand->add_option("--technique,-t", render.technique, "Technique name (see `shadowlab list`)")
    ->capture_default_str();
  renderCommand->add_option("--set,-s", render.settings, "Technique parameter, key=value (repeatable)");
  renderCommand->add_option("--scene-set", render.sceneOverrides, "Scene value, /json/pointer=value, e.g. /lights/0/size=2 (repeatable)");
  renderCommand->add_option("--resolution,-r", render.resolution, "Image size WxH (default: the scene camera's)");
  renderCommand->add_option("--out,-o", render.outDir, "Output directory (replaced atomically; see --force)")->capture_default_str();
  addForceFlag(renderCommand, render.force);
  renderCommand->add_option("--light", render.lightIndex, "Index of the scene light that casts shadows")
    ->capture_default_str();
  renderCommand->add_flag("--quiet,-q", render.quiet, "Print nothing on success");
  renderCommand->add_flag("--progress", render.progress,
    "A frame expected to take 20 s or more (reference-sm, dcs on large meshes) prints its estimate and progress "
    "unless --quiet; --progress prints them with --quiet too");
  return { renderCommand, [&render] { return sl::runRender(render, std::cerr); }, {} };
}

Command addReferenceCommand(CLI::App& app, sl::ReferenceOptions& reference)
{
  CLI::App* referenceCommand = app.add_subcommand("reference",
    "Ray-traced ground truth (Embree): the visible fraction of the light for every pixel the pipeline shades");
  referenceCommand->add_option("scene", reference.sceneFile, "Scene file (JSON)")->required();
  CLI::Option* referenceSamples = referenceCommand
    ->add_option("--reference-samples,-n", reference.samples,
      "Light samples per pixel of the ray-traced reference (with --light-samples: 16, 64 or 256, default 16); "
      "old spelling --samples")
    ->capture_default_str();
  const RenamedOption oldSamples =
    addOldSpelling(referenceCommand, "--samples", reference.samples, referenceSamples, "--reference-samples");
  referenceCommand->add_option("--scene-set", reference.sceneOverrides, "Scene value, /json/pointer=value (repeatable)");
  CLI::Option* referenceSampling =
    referenceCommand->add_option("--sampling", reference.sampling, "stratified | halton")->capture_default_str();
  CLI::Option* referenceLightSamples = referenceCommand
    ->add_option("--light-samples", reference.lightSamples,
      "Shared light-sample set, the samples of technique dcs (" + joinedLightSamplePatterns() +
        "); also writes sample_crossings and light_sample_mask")
    ->excludes(referenceSampling);
  referenceCommand->add_option("--seed", reference.seed, "Seed (results are deterministic for a seed)")
    ->check(seedRange())
    ->capture_default_str();
  referenceCommand
    ->add_option("--msaa", reference.msaa,
      "1 | 4: with 4, trace at each sample position of a 4x multisampled G-buffer and average the covered samples "
      "(the like-for-like reference of techniques rendered with msaa=4)")
    ->capture_default_str();
  referenceCommand->add_option("--resolution,-r", reference.resolution, "Image size WxH (default: the scene camera's)");
  referenceCommand->add_option("--out,-o", reference.outDir, "Output directory (replaced atomically; see --force)")->capture_default_str();
  addForceFlag(referenceCommand, reference.force);
  referenceCommand->add_option("--light", reference.lightIndex, "Index of the scene light")->capture_default_str();
  referenceCommand->add_option("--threads", reference.threads, "Worker threads (0: all cores)")->capture_default_str();
  referenceCommand->add_option("--tile", reference.tile,
    "K/N: trace only row tile K of N (merged by reference-merge, bit for bit the whole reference)");
  referenceCommand->add_flag("--quiet,-q", reference.quiet, "Print nothing on success");
  addProgressFlag(referenceCommand, reference.progress);
  return { referenceCommand,
    [&reference, referenceSamples, referenceLightSamples, oldSamples] {
      reference.samplesGiven = referenceSamples->count() > 0 || oldSamples.old->count() > 0;
      reference.samplesOption = oldSamples.old->count() > 0 ? "--samples" : "--reference-samples";
      reference.lightSamplesGiven = referenceLightSamples->count() > 0;
      return sl::runReference(reference, std::cerr);
    },
    { oldSamples } };
}

Command addReferenceMergeCommand(CLI::App& app, sl::ReferenceMergeOptions& merge)
{
  CLI::App* mergeCommand = app.add_subcommand("reference-merge",
    "Row tiles of one reference (reference --tile K/N, every K once) into one reference directory");
  mergeCommand->add_option("tiles", merge.tileDirs, "Tile directories (reference --tile K/N --out DIR)")->required();
  mergeCommand->add_option("--out,-o", merge.outDir, "Output directory (replaced atomically; see --force)")
    ->capture_default_str();
  addForceFlag(mergeCommand, merge.force);
  mergeCommand->add_flag("--quiet,-q", merge.quiet, "Print nothing on success");
  return { mergeCommand, [&merge] { return sl::runReferenceMerge(merge, std::cerr); }, {} };
}

Command addCompareCommand(CLI::App& app, sl::CompareOptions& compare)
{
  CLI::App* compareCommand =
    app.add_subcommand("compare", "Error metrics of TEST.vti against REF.vti (RMSE, MAE, max, >0.05; all and penumbra)");
  compareCommand->add_option("test", compare.testFile, "buffers.vti of the technique")->required();
  compareCommand->add_option("reference", compare.referenceFile, "buffers.vti of the reference")->required();
  compareCommand->add_option("--array", compare.array, "Array to compare")->capture_default_str();
  compareCommand->add_option("--out,-o", compare.outDir, "Output directory (replaced atomically; see --force)")->capture_default_str();
  addForceFlag(compareCommand, compare.force);
  compareCommand->add_flag("--quiet,-q", compare.quiet, "Print nothing on success");
  return { compareCommand, [&compare] { return sl::runCompare(compare, std::cerr); }, {} };
}

Command addBenchCommand(CLI::App& app, sl::BenchOptions& bench, std::vector<std::string>& techniqueList)
{
  CLI::App* benchCommand = app.add_subcommand("bench",
    "Speed against error: scenes x techniques x sweeps, each configuration in its own process");
  benchCommand->add_option("scenes", bench.sceneFiles, "Scene files (none with --collect: the plan names them)");
  CLI::Option* techniques = benchCommand
    ->add_option("--technique,-t", techniqueList,
      "Technique names, comma-separated or repeated (default hard,pcf); old spelling --techniques")
    ->expected(1) // one value per -t: a scene after it stays a scene
    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
    ->allow_extra_args(false);
  const RenamedOption oldTechniques =
    addOldSpelling(benchCommand, "--techniques", bench.techniques, techniques, "-t/--technique");
  benchCommand->add_option("--sweep", bench.sweeps, "key=v1,v2,... (repeatable: all combinations)");
  benchCommand->add_option("--set,-s", bench.settings, "key=value for every technique that has the key");
  benchCommand->add_option("--scene-set", bench.sceneOverrides, "Scene value for every scene, /json/pointer=value");
  benchCommand->add_option("--scene-sweep", bench.sceneSweeps,
    "Scene values to sweep, /json/pointer=v1,v2,... e.g. /lights/0/size=0.25,0.5,1,2,4 (repeatable: all combinations)");
  benchCommand->add_option("--repeat", bench.repeat, "Timed frames after one warm-up frame (median, min and max reported)")
    ->capture_default_str();
  benchCommand
    ->add_option("--resolution,-r", bench.resolution,
      "Image size WxH, or a comma list (128x128,256x256,...): every configuration at every size, a resolution column, "
      "charts per size and cost_growth_pixels_<scene>.png (frame and technique-pass time against pixels, log-log)")
    ->capture_default_str();
  CLI::Option* referenceSamples = benchCommand
    ->add_option("--reference-samples", bench.referenceSamples,
      "Light samples per pixel of the ray-traced reference (not a technique's `--set samples=`); old spelling --samples")
    ->capture_default_str();
  const RenamedOption oldSamples =
    addOldSpelling(benchCommand, "--samples", bench.referenceSamples, referenceSamples, "--reference-samples");
  benchCommand->add_option("--cache", bench.cacheDir, "Cache of ray-traced references")->capture_default_str();
  benchCommand->add_option("--out,-o", bench.outDir, "Output directory (replaced atomically; see --force)")->capture_default_str();
  benchCommand->add_option("--depth-profile", bench.depthProfile,
    "A buffer (e.g. texel_ratio_t) binned over the eye's depth: depth_profile.csv and depth_profile_<scene>.png");
  benchCommand->add_option("--depth-bins", bench.depthBins, "Bins of --depth-profile, equal depth ratios")
    ->capture_default_str();
  benchCommand->add_option("--depth-range", bench.depthRange,
    "near,far eye depths of --depth-profile's bins (default: the binned pixels' range)");
  benchCommand->add_option("--view-stats", bench.viewStats,
    "Buffers (e.g. texel_ratio,perspective_factor) whose max, 99th percentile and mean over the view become bench.csv "
    "columns and charts against the first --sweep key");
  benchCommand->add_option("--baseline", bench.baselineDir,
    "An earlier bench's output DIR (with bench.csv): summary.md compares RMSE, penumbra RMSE and p99 per technique x "
    "scene with its rows and flags the worse ones (RMSE up by more than 1e-4 and 1 %); bench.csv gains baseline_rmse and "
    "rmse_delta");
  benchCommand->add_option("--plan", bench.planDir,
    "Write the bench as jobs (jobs.txt, Slurm job arrays: submit.sh) into DIR instead of running it (docs/cluster.md)");
  benchCommand->add_option("--collect", bench.collectDir,
    "Merge what the tasks of the plan in DIR wrote into --out (bench.csv, ...); names missing and failed tasks");
  benchCommand->add_option("--slurm-partition", bench.slurmPartition, "With --plan: the Slurm partition (-p)");
  benchCommand->add_option("--slurm-time", bench.slurmTime, "With --plan: time limit per task (MM, HH:MM:SS, D-HH:MM)");
  benchCommand->add_option("--slurm-gpus", bench.slurmGpus, "With --plan: GPUs per task (--gres=gpu:N; 0: none)")
    ->capture_default_str();
  benchCommand->add_option("--slurm-throttle", bench.slurmThrottle,
    "With --plan: at most N tasks of an array at once (0: no limit)")->capture_default_str();
  benchCommand->add_option("--reference-tiles", bench.referenceTiles,
    "With --plan: each reference traced as N row tiles (array tasks), merged bit for bit")->capture_default_str();
  addForceFlag(benchCommand, bench.force);
  benchCommand->add_flag("--quiet,-q", bench.quiet, "Print only the summary line");
  addProgressFlag(benchCommand, bench.progress);
  return { benchCommand,
    [&bench, &techniqueList, techniques, oldSamples] {
      if (techniques->count() > 0)
      {
        bench.techniques = joinedTechniqueList(techniqueList);
      }
      bench.referenceSamplesOption = oldSamples.old->count() > 0 ? "--samples" : "--reference-samples";
      return sl::runBench(bench, std::cerr);
    },
    { oldTechniques, oldSamples } };
}

Command addBenchRunCommand(CLI::App& app, sl::BenchRunOptions& benchRun)
{
  CLI::App* benchRunCommand = app.add_subcommand("bench-run", "One bench configuration (started by bench)");
  benchRunCommand->group(""); // hidden from --help
  benchRunCommand->add_option("scene", benchRun.sceneFile)->required();
  benchRunCommand->add_option("--technique", benchRun.technique)->required();
  benchRunCommand->add_option("--set", benchRun.settings);
  benchRunCommand->add_option("--scene-set", benchRun.sceneOverrides);
  benchRunCommand->add_option("--resolution", benchRun.resolution)->required();
  benchRunCommand->add_option("--repeat", benchRun.repeat);
  benchRunCommand->add_option("--reference", benchRun.referenceFile);
  benchRunCommand->add_option("--result", benchRun.resultFile)->required();
  benchRunCommand->add_option("--depth-profile", benchRun.depthProfile);
  benchRunCommand->add_option("--depth-bins", benchRun.depthBins);
  benchRunCommand->add_option("--depth-range", benchRun.depthRange);
  benchRunCommand->add_option("--view-stats", benchRun.viewStats);
  return { benchRunCommand, [&benchRun] { return sl::runBenchConfiguration(benchRun); }, {} };
}

Command addProbeCommand(CLI::App& app, sl::ProbeOptions& probe)
{
  CLI::App* probeCommand = app.add_subcommand("probe",
    "Replay one pixel on the technique's CPU twin and record every step (probe.json, probe.vtm, probe.png)");
  probeCommand->add_option("scene", probe.sceneFile, "Scene file (JSON)")->required();
  probeCommand->add_option("--technique,-t", probe.technique, "Technique name (see `shadowlab list`)")->capture_default_str();
  probeCommand->add_option("--pixel", probe.pixel, "X,Y in image coordinates, row 0 at the bottom (as buffers.vti)");
  probeCommand->add_option("--pick", probe.pick,
    "X,Y,Z (world coordinates; `--pick world X,Y,Z` too): the pixel that shows this visible surface point");
  probeCommand->add_option("--set,-s", probe.settings, "Technique parameter, key=value (repeatable)");
  probeCommand->add_option("--scene-set", probe.sceneOverrides, "Scene value, /json/pointer=value (repeatable)");
  probeCommand->add_option("--resolution,-r", probe.resolution, "Image size WxH (default: the scene camera's)");
  probeCommand->add_option("--out,-o", probe.outDir, "Output directory (replaced atomically; see --force)")->capture_default_str();
  addForceFlag(probeCommand, probe.force);
  probeCommand->add_option("--light", probe.lightIndex, "Index of the scene light that casts shadows")->capture_default_str();
  probeCommand->add_flag("--quiet,-q", probe.quiet, "Print nothing on success");
  return { probeCommand, [&probe] { return sl::runProbe(probe, std::cerr); }, {} };
}

Command addViewCommand(CLI::App& app, sl::ViewOptions& view)
{
  CLI::App* viewCommand = app.add_subcommand("view",
    "A desktop window on the pipeline's frames: keys cycle techniques, buffers and parameters, a click probes a "
    "pixel (h in the window lists the keys)");
  viewCommand->add_option("scene", view.sceneFile, "Scene file (JSON)")->required();
  viewCommand->add_option("--technique,-t", view.technique, "Technique to start with")->capture_default_str();
  viewCommand->add_option("--set,-s", view.settings, "Parameter of that technique, key=value (repeatable)");
  viewCommand->add_option("--scene-set", view.sceneOverrides, "Scene value, /json/pointer=value (repeatable)");
  viewCommand->add_option("--resolution,-r", view.resolution, "Image size WxH (default: the scene camera's)");
  viewCommand->add_option("--light", view.lightIndex, "Index of the scene light that casts shadows")
    ->capture_default_str();
  viewCommand->add_option("--record", view.recordFile,
    "Write the session's events to FILE (VTK's event recorder); an existing file is replaced only when it is a "
    "recording (see --force)");
  viewCommand->add_option("--play", view.playFile, "Replay the events in FILE (as --record wrote them), then exit");
  viewCommand->add_flag("--force", view.force,
    "Let --record replace an existing file that is not a recording (never an input: the scene, its meshes and "
    "textures, --play, a file parameter)");
  viewCommand->add_option("--screenshot-dir", view.screenshotDir, "Where the s key saves screenshots (PNG)")
    ->capture_default_str();
  return { viewCommand, [&view] { return sl::runView(view, std::cout); }, {} };
}

Command addMontageCommand(CLI::App& app, sl::MontageCommandOptions& montage)
{
  CLI::App* montageCommand = app.add_subcommand("montage",
    "One buffer of several runs side by side on one colour scale, labelled from each run's stats.json");
  montageCommand->add_option("runs", montage.runDirs, "Output directories of render or reference")->required();
  montageCommand->add_option("--buffer,-b", montage.buffer, "Buffer to show (a scalar array of buffers.vti)")->required();
  montageCommand->add_option("--out,-o", montage.outFile, "PNG to write (replaced atomically; see --force)")->capture_default_str();
  montageCommand->add_option("--reference", montage.referenceDir,
    "Run whose visibility is the truth: each panel is labelled with its RMSE against it");
  montageCommand->add_flag("--force", montage.force,
    "Let --out replace an existing file montage did not write (never an input: a RUN_DIR or a file in one)");
  montageCommand->add_flag("--quiet,-q", montage.quiet, "Print nothing on success");
  return { montageCommand, [&montage] { return sl::runMontage(montage, std::cerr); }, {} };
}

Command addLessonsCommand(CLI::App& app, sl::LessonsOptions& lessons)
{
  CLI::App* lessonsCommand = app.add_subcommand("lessons",
    "Lesson pages (Markdown) with figures and numbers from runs made now (src/lessons/)");
  lessonsCommand->add_option("--out,-o", lessons.outDir,
    "Output directory (replaced atomically; see --force); `--out docs/lessons` regenerates the pages in the source "
    "tree")->capture_default_str();
  lessonsCommand->add_flag("--list", lessons.list, "Print each lesson's name and title, one per line; run nothing");
  lessonsCommand->add_option("--resolution,-r", lessons.resolution, "Image size WxH of every run")->capture_default_str();
  lessonsCommand->add_option("--only", lessons.only,
    "Only this lesson (repeatable); the other lessons of an existing --out are kept");
  addForceFlag(lessonsCommand, lessons.force);
  lessonsCommand->add_flag("--quiet,-q", lessons.quiet, "Print nothing on success");
  addProgressFlag(lessonsCommand, lessons.progress);
  return { lessonsCommand, [&lessons] { return sl::runLessons(lessons, lessons.list ? std::cout : std::cerr); }, {} };
}

Command addDifferentialCommand(
  CLI::App& app, sl::DifferentialCommandOptions& differential, std::vector<std::string>& techniqueList)
{
  CLI::App* differentialCommand = app.add_subcommand("differential",
    "Every technique and each enumerated choice against the ray tracer on random scenes (seeded); exit 4 on a failure");
  differentialCommand->add_option("--seeds", differential.seeds, "A..B or A,B,...")->capture_default_str();
  CLI::Option* techniques = differentialCommand->add_option("--technique,-t", techniqueList,
    "Technique names, comma-separated or repeated (default: all)")
    ->expected(1)
    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
    ->allow_extra_args(false);
  differentialCommand->add_option("--choice", differential.choice,
    "Only this choice: default, or key=value of an enumerated parameter (default: every choice)");
  differentialCommand->add_option("--max-side", differential.maxSide, "Longest image side of the random scenes")
    ->capture_default_str();
  CLI::Option* referenceSamples = differentialCommand
    ->add_option("--reference-samples", differential.samples,
      "Light samples per pixel of the ray-traced reference (stratified); old spelling --samples")
    ->capture_default_str();
  const RenamedOption oldSamples = addOldSpelling(
    differentialCommand, "--samples", differential.samples, referenceSamples, "--reference-samples");
  differentialCommand->add_option("--out,-o", differential.outDir, "Output directory: report.md, differential.json, "
    "seed-S/scene.json (replaced atomically; see --force)")->capture_default_str();
  addForceFlag(differentialCommand, differential.force);
  differentialCommand->add_flag("--quiet,-q", differential.quiet, "Print only failures and the table");
  addProgressFlag(differentialCommand, differential.progress);
  return { differentialCommand,
    [&differential, &techniqueList, techniques, oldSamples] {
      if (techniques->count() > 0)
      {
        differential.techniques = joinedTechniqueList(techniqueList);
      }
      differential.samplesOption = oldSamples.old->count() > 0 ? "--samples" : "--reference-samples";
      return sl::runDifferential(differential, std::cerr);
    },
    { oldSamples } };
}

Command addListCommand(CLI::App& app, sl::ListOptions& list)
{
  CLI::App* listCommand = app.add_subcommand("list",
    "List techniques with their parameters, defaults and ranges (all, or only the TECHNIQUEs named)");
  listCommand->add_option("techniques", list.techniques,
    "Only these techniques (names, or comma-separated lists of names)");
  listCommand->add_flag("--json", list.json, "Machine-readable output");
  listCommand->add_flag("--structures", list.structures,
    "List the light-space structures instead, each with the techniques that use it");
  return { listCommand, [&list] { return sl::runList(list, std::cout); }, {} };
}

// `--pick world X,Y,Z` (two words) becomes `--pick "world X,Y,Z"` before CLI11 sees it, so that --pick takes one
// value (`--pick X,Y,Z`, and a scene after it is not taken for a second one) and the old form keeps working and is
// named as typed in errors. Any word of letters after --pick is joined so (`--pick screen 0,0,0` is refused by
// probe, naming both words).
std::vector<std::string> joinedPickArguments(int argc, char** argv)
{
  std::vector<std::string> arguments(argv, argv + argc);
  for (std::size_t i = 0; i + 2 < arguments.size(); ++i)
  {
    const std::string& word = arguments[i + 1];
    const bool letters = !word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ") == std::string::npos;
    if (arguments[i] == "--pick" && letters)
    {
      arguments[i + 1] = word + " " + arguments[i + 2];
      arguments.erase(arguments.begin() + static_cast<std::ptrdiff_t>(i) + 2);
    }
  }
  return arguments;
}

// Runs the parsed command, each error kind one line with its exit code (docs/outputs.md, "Outputs and exit codes").
int runParsedCommand(const std::vector<Command>& commands)
{
  try
  {
    for (const Command& command : commands)
    {
      if (command.command->parsed())
      {
        for (const RenamedOption& renamed : command.renamed)
        {
          if (renamed.old->count() > 0 && renamed.replacement->count() > 0)
          {
            throw sl::InputError(renamed.oldName + " and " + renamed.newSpelling + ": the same option, given twice (" +
              renamed.oldName + " is the old spelling)");
          }
          if (renamed.old->count() > 0)
          {
            std::cerr << "shadowlab: note: " << renamed.oldName << " is now " << renamed.newSpelling
                      << "; the old spelling goes in the next release\n";
          }
        }
        return command.run();
      }
    }
  }
  catch (const sl::InputError& error)
  {
    std::cerr << "shadowlab: error: " << sl::printable(error.what()) << "\n";
    return 1;
  }
  catch (const sl::GraphicsError& error)
  {
    std::cerr << "shadowlab: graphics error: " << sl::printable(error.what()) << "\n";
    return 2;
  }
  catch (const std::exception& error)
  {
    std::cerr << "shadowlab: internal error: " << sl::printable(error.what()) << "\n";
    return 3;
  }
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  CLI::App app{ "ShadowLab: real-time shadow algorithms, rendered and opened up.\n"
                "Every technique writes its image, visibility and internal buffers (VTK image data for ParaView)." };
  app.require_subcommand(1);

  // Every error is one line on stderr with a nonzero exit (docs/outputs.md, "Outputs and exit codes").
  sl::installOutputSignalHandlers();
  sl::installVtkOutputWindow(); // VTK's own messages reach the user only through the error path

  sl::RenderOptions render;
  sl::ReferenceOptions reference;
  sl::ReferenceMergeOptions referenceMerge;
  sl::CompareOptions compare;
  sl::BenchOptions bench;
  sl::BenchRunOptions benchRun;
  sl::ProbeOptions probe;
  sl::ViewOptions view;
  sl::MontageCommandOptions montage;
  sl::LessonsOptions lessons;
  sl::DifferentialCommandOptions differential;
  sl::ListOptions list;
  std::vector<std::string> benchTechniques;
  std::vector<std::string> differentialTechniques;
  // In --help's order.
  const std::vector<Command> commands = { addRenderCommand(app, render), addReferenceCommand(app, reference),
    addReferenceMergeCommand(app, referenceMerge), addCompareCommand(app, compare), addBenchCommand(app, bench, benchTechniques), addBenchRunCommand(app, benchRun),
    addProbeCommand(app, probe), addViewCommand(app, view), addMontageCommand(app, montage),
    addLessonsCommand(app, lessons), addDifferentialCommand(app, differential, differentialTechniques), addListCommand(app, list) };

  try
  {
    const std::vector<std::string> arguments = joinedPickArguments(argc, argv);
    std::vector<const char*> pointers;
    for (const std::string& argument : arguments)
    {
      pointers.push_back(argument.c_str());
    }
    app.parse(static_cast<int>(pointers.size()), pointers.data());
  }
  catch (const CLI::CallForHelp& help)
  {
    return app.exit(help);
  }
  catch (const CLI::CallForAllHelp& help)
  {
    return app.exit(help);
  }
  catch (const CLI::ParseError& error)
  {
    // CLI11 would exit with its own codes (100+) and two lines; the contract is one line and exit 1.
    std::cerr << "shadowlab: error: " << sl::printable(error.what()) << " (see shadowlab --help)\n";
    return 1;
  }
  return runParsedCommand(commands);
}
