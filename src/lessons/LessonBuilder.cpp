#include "lessons/LessonBuilder.h"

#include "core/Error.h"
#include "core/NamedImage.h"
#include "io/ImageIO.h"
#include "lessons/Lesson.h"
#include "lessons/LessonRegistry.h"
#include "lessons/RunMontage.h"
#include "metrics/DepthProfile.h"
#include "metrics/ErrorMetrics.h"
#include "output/OutputWriter.h"
#include "probe/Probe.h"
#include "frame/FrameResult.h"
#include "pipeline/ShadowRenderer.h"
#include "reference/ReferenceRenderer.h"
#include "scene/Scene.h"
#include "vis/Montage.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <fstream>
#include <sstream>

namespace sl
{

namespace fs = std::filesystem;

struct LessonBuilder::Run
{
  LessonRunSpec spec;
  bool isReference = false;
  std::vector<NamedImage> buffers;
  nlohmann::json stats;
  // Rendered runs: the frame and its scene, for probes.
  std::optional<FrameResult> frame;
  std::optional<Scene> scene;
};

namespace
{

std::string scenePath(const std::string& dataset)
{
  return "datasets/" + dataset + "/scene.json";
}

std::string joinedWords(const std::vector<std::string>& words, const std::string& separator)
{
  std::string text;
  for (const std::string& word : words)
  {
    text += (text.empty() ? "" : separator) + word;
  }
  return text;
}

// A measured value as the page prints it: integers exactly, others with 4 significant digits.
std::string measuredText(const nlohmann::json& value)
{
  if (value.is_number_integer() || value.is_number_unsigned())
  {
    return value.dump();
  }
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value.get<double>());
  return text;
}

// A shell word: quoted when it has characters the shell would read.
std::string shellWord(const std::string& word)
{
  if (word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=,:") == std::string::npos)
  {
    return word;
  }
  std::string quoted = "'";
  for (char c : word)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

std::string codeList(const std::vector<std::string>& items)
{
  std::vector<std::string> code;
  for (const std::string& item : items)
  {
    code.push_back("`" + item + "`");
  }
  return joinedWords(code, " ");
}

} // namespace

LessonBuilder::LessonBuilder(
  const Lesson& lesson, const LessonsSettings& settings, ShadowRenderer& renderer, fs::path lessonDir)
  : lesson_(lesson)
  , settings_(settings)
  , renderer_(renderer)
  , dir_(std::move(lessonDir))
  , start_(std::chrono::steady_clock::now())
{
  fs::create_directories(dir_ / "runs");
}

LessonBuilder::~LessonBuilder() = default;

void LessonBuilder::sceneNote(const std::string& markdown)
{
  sceneNotes_.push_back(markdown);
}

const LessonBuilder::Run& LessonBuilder::run(const std::string& name) const
{
  for (const std::unique_ptr<Run>& run : runs_)
  {
    if (run->spec.name == name)
    {
      return *run;
    }
  }
  SL_CHECK_MSG(false, "lesson ", lesson_.name, ": no run named ", name);
  return *runs_.front(); // not reached
}

void LessonBuilder::addRun(std::unique_ptr<Run> run)
{
  for (const std::unique_ptr<Run>& existing : runs_)
  {
    SL_CHECK_MSG(existing->spec.name != run->spec.name, "lesson ", lesson_.name, ": run ", run->spec.name, " twice");
  }
  const fs::path runDir = dir_ / "runs" / run->spec.name;
  fs::create_directories(runDir);
  writeJson(run->stats, runDir / "stats.json");
  runs_.push_back(std::move(run));
}

void LessonBuilder::render(const LessonRunSpec& spec)
{
  const Scene scene = loadScene(settings_.datasets / spec.dataset / "scene.json", spec.sceneOverrides);
  RenderRequest request;
  request.technique = spec.technique;
  request.settings = spec.settings;
  request.resolution = settings_.resolution;
  FrameResult frame = renderer_.render(scene, request);

  OutputContext context;
  context.sceneFile = scenePath(spec.dataset); // as the page's commands give it, from the repository root
  for (const SceneObject& object : scene.objects)
  {
    context.droppedDegenerateTriangles += object.droppedDegenerateTriangles;
  }
  auto result = std::make_unique<Run>();
  result->spec = spec;
  result->stats = frameStats(frame, context);
  result->stats["scene_overrides"] = spec.sceneOverrides;
  result->stats["settings"] = spec.settings;
  if (!spec.comparedWith.empty())
  {
    const Run& truth = run(spec.comparedWith);
    const ComparisonInputNames names{ spec.name, spec.comparedWith, "visibility" };
    const ErrorMetrics metrics = computeErrorMetrics(frame.find("visibility")->image,
      findNamed(truth.buffers, "visibility")->image, frame.find("coverage")->image,
      findNamed(truth.buffers, "coverage")->image, names);
    result->stats["error"] = metricsJson(metrics);
    result->stats["compared_with"] = spec.comparedWith;
  }
  for (const std::string& buffer : spec.depthProfiles)
  {
    DepthProfileSettings profile;
    profile.buffer = buffer;
    profile.bins = spec.depthBins;
    result->stats["depth_profile"][buffer] = depthProfileJson(depthProfile(frame, profile));
  }
  result->buffers = frame.buffers;
  result->frame = std::move(frame);
  result->scene = scene;
  addRun(std::move(result));
}

void LessonBuilder::reference(const std::string& name, const std::string& dataset,
  const std::vector<std::string>& sceneOverrides)
{
  const Scene scene = loadScene(settings_.datasets / dataset / "scene.json", sceneOverrides);
  RenderRequest request;
  request.gbufferOnly = true;
  request.resolution = settings_.resolution;
  FrameResult gbuffer = renderer_.render(scene, request);

  const ReferenceInputs inputs = referenceInputsOf(gbuffer, scene, 0);
  ReferenceSettings referenceSettings;
  referenceSettings.samples = settings_.referenceSamples;
  referenceSettings.sampling = LightSampling::Stratified;
  referenceSettings.seed = 1;
  const ReferenceResult traced = renderReference(inputs, referenceSettings);

  auto result = std::make_unique<Run>();
  result->spec.name = name;
  result->spec.dataset = dataset;
  result->spec.sceneOverrides = sceneOverrides;
  result->isReference = true;
  result->buffers.push_back({ "visibility", traced.visibility, "", "ray-traced visible fraction of the light (ground truth)" });
  result->buffers.push_back({ "visibility_stderr", traced.standardError, "", "standard error of the estimate (Bernoulli bound)" });
  for (NamedImage& named : gbuffer.buffers)
  {
    result->buffers.push_back(std::move(named));
  }
  // The keys of `shadowlab reference`'s stats.json.
  result->stats = {
    { "command", "reference" },
    { "scene", scenePath(dataset) },
    { "scene_overrides", sceneOverrides },
    { "light_index", 0 },
    { "resolution", { settings_.resolution.x, settings_.resolution.y } },
    { "samples", settings_.referenceSamples },
    { "sampling", "stratified" },
    { "seed", 1 },
    { "ray_offset", referenceRayOffset(scene, referenceSettings) },
    { "rays_traced", traced.raysTraced },
    { "seconds", traced.seconds },
    { "rays_per_second", traced.raysPerSecond },
    { "gl_renderer", gbuffer.glRenderer },
  };
  result->stats["buffers"] = bufferSummaries(result->buffers);
  addRun(std::move(result));
}

void LessonBuilder::montage(const std::string& stem, const std::string& caption, const std::vector<std::string>& runs,
  const std::string& buffer, std::optional<double> clipQuantile, std::optional<double> signedLogLinearQuantile)
{
  std::vector<MontagePanel> panels;
  std::vector<nlohmann::json> stats;
  const BufferSpec spec = runBufferSpec(run(runs.front()).stats, buffer);
  for (const std::string& name : runs)
  {
    const Run& source = run(name);
    const NamedImage* values = findNamed(source.buffers, buffer);
    SL_CHECK_MSG(values && values->image.components == 1, "lesson ", lesson_.name, ": run ", name, " has no scalar buffer ", buffer);
    SL_CHECK_MSG(runBufferSpec(source.stats, buffer).kind == spec.kind, "lesson ", lesson_.name, ": ", buffer,
      " is not of one kind in the runs of ", stem);
    panels.push_back({ values->image, runValueMask(source.buffers, *values, spec), {} });
    stats.push_back(source.stats);
  }
  const std::vector<std::vector<std::string>> labels = montageRunLabels(runs, stats);
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    panels[p].labels = labels[p];
  }
  MontageOptions options;
  options.title = buffer;
  options.unit = spec.unit;
  options.kind = spec.kind;
  options.categoryLabels = spec.categoryLabels;
  options.clipQuantile = clipQuantile;
  options.signedLogLinearQuantile = signedLogLinearQuantile;
  options.commonLines = montageCommonLabels(stats);
  writePng(dir_ / (stem + ".png"), renderMontage(panels, options));
  figures_.push_back({ stem + ".png", caption });
}

void LessonBuilder::errorMontage(const std::string& stem, const std::string& caption, const std::vector<std::string>& runs)
{
  std::vector<MontagePanel> panels;
  std::vector<nlohmann::json> stats;
  for (const std::string& name : runs)
  {
    const Run& source = run(name);
    SL_CHECK_MSG(!source.spec.comparedWith.empty(), "lesson ", lesson_.name, ": run ", name, " was compared with nothing");
    const Run& truth = run(source.spec.comparedWith);
    const Comparison comparison = compareImages(findNamed(source.buffers, "visibility")->image,
      findNamed(truth.buffers, "visibility")->image, findNamed(source.buffers, "coverage")->image,
      findNamed(truth.buffers, "coverage")->image, ComparisonInputNames{ name, truth.spec.name, "visibility" });
    MontagePanel panel;
    panel.values = comparison.error;
    panel.validMask = ImageU8(comparison.mask.width, comparison.mask.height, 1);
    for (std::size_t i = 0; i < comparison.mask.pixelCount(); ++i)
    {
      panel.validMask.data[i] = comparison.mask.data[i] > 0.5f ? 1 : 0;
    }
    panels.push_back(std::move(panel));
    stats.push_back(source.stats);
  }
  const std::vector<std::vector<std::string>> labels = montageRunLabels(runs, stats);
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    panels[p].labels = labels[p];
    panels[p].labels.push_back("vs " + run(runs[p]).spec.comparedWith);
  }
  MontageOptions options;
  options.title = "visibility error (run - truth)";
  options.kind = BufferKind::Signed;
  options.commonLines = montageCommonLabels(stats);
  writePng(dir_ / (stem + ".png"), renderMontage(panels, options));
  figures_.push_back({ stem + ".png", caption });
}

void LessonBuilder::probe(
  const std::string& stem, const std::string& caption, const std::string& runName, const LessonPixel& pick)
{
  const Run& source = run(runName);
  SL_CHECK_MSG(source.frame && source.scene, "lesson ", lesson_.name, ": run ", runName, " is not a rendered run");
  const ImageF& coverage = findNamed(source.buffers, "coverage")->image;
  const NamedImage* receives = findNamed(source.buffers, "receives_shadows");
  const ImageF* values = nullptr;
  const ImageF* truth = nullptr;
  const ImageF* truthCoverage = nullptr;
  if (pick.rule == LessonPixel::Rule::LargestValue)
  {
    const NamedImage* buffer = findNamed(source.buffers, pick.buffer);
    SL_CHECK_MSG(buffer && buffer->image.components == 1, "lesson ", lesson_.name, ": run ", runName,
      " has no scalar buffer ", pick.buffer);
    values = &buffer->image;
  }
  else
  {
    SL_CHECK_MSG(!source.spec.comparedWith.empty(), "lesson ", lesson_.name, ": run ", runName, " was compared with nothing");
    const Run& other = run(source.spec.comparedWith);
    values = &findNamed(source.buffers, "visibility")->image;
    truth = &findNamed(other.buffers, "visibility")->image;
    truthCoverage = &findNamed(other.buffers, "coverage")->image;
  }
  std::optional<glm::ivec2> chosen;
  double best = 0.0;
  double bestDistance = 0.0;
  for (int y = 0; y < coverage.height; ++y)
  {
    for (int x = 0; x < coverage.width; ++x)
    {
      const bool usable = coverage.at(x, y) > 0.5f && (!receives || receives->image.at(x, y) > 0.5f) &&
        (!truthCoverage || truthCoverage->at(x, y) > 0.5f) && std::isfinite(values->at(x, y));
      if (!usable)
      {
        continue;
      }
      const double score = truth ? std::abs(double(values->at(x, y)) - double(truth->at(x, y))) : values->at(x, y);
      // Ties (within float rounding) go to the pixel nearest the image's centre, away from the borders.
      const double centreDistance = glm::length(glm::dvec2(x, y) - 0.5 * glm::dvec2(coverage.width - 1, coverage.height - 1));
      const double tie = 1e-6 * std::max(1.0, std::abs(best));
      if (!chosen || score > best + tie || (score >= best - tie && centreDistance < bestDistance))
      {
        chosen = glm::ivec2(x, y);
        best = std::max(best, score);
        bestDistance = centreDistance;
      }
    }
  }
  SL_CHECK_MSG(chosen, "lesson ", lesson_.name, ": run ", runName, " has no pixel to probe");
  const ProbeResult result = probePixel(*source.frame, *source.scene, 0, *chosen);
  writePng(dir_ / (stem + ".png"), probeFigure(result, *source.frame, *source.scene));

  const std::string pixelText = format(chosen->x, ",", chosen->y);
  const std::string why = pick.rule == LessonPixel::Rule::LargestValue
    ? "the covered pixel with the largest `" + pick.buffer + "`"
    : "the covered pixel whose visibility is furthest from `" + source.spec.comparedWith + "`'s";
  figures_.push_back({ stem + ".png",
    caption + " Pixel " + pixelText + " of `" + runName + "` (row 0 at the bottom), " + why +
      ", replayed on the technique's CPU twin, whose visibility " +
      (result.agrees() ? "agrees with the GPU's" : "DIFFERS from the GPU's beyond the tests' tolerance") +
      ". The `shadowlab probe` command under \"Commands to try next\" writes every recorded quantity, with its unit "
      "and the paper's equation (probe.json), and the figure's data for ParaView (probe.vtm)." });

  std::string command = "shadowlab probe " + scenePath(source.spec.dataset) + " -t " + source.spec.technique;
  for (const std::string& setting : source.spec.settings)
  {
    command += " --set " + shellWord(setting);
  }
  for (const std::string& sceneOverride : source.spec.sceneOverrides)
  {
    command += " --scene-set " + shellWord(sceneOverride);
  }
  commands_.push_back({ "Probe the pixel of the figure yourself (probe.json, probe.vtm for ParaView, probe.png), "
                        "or another one:",
    command + " --pixel " + pixelText + " -r " + resolutionText() + " --out out/probe-" + runName });
}

double LessonBuilder::value(const std::string& runName, const std::string& pointer) const
{
  const nlohmann::json& stats = run(runName).stats;
  const nlohmann::json::json_pointer path(pointer);
  SL_CHECK_MSG(stats.contains(path) && stats[path].is_number(), "lesson ", lesson_.name, ": runs/", runName,
    "/stats.json has no number at ", pointer);
  return stats[path].get<double>();
}

void LessonBuilder::measure(const std::string& quantity, const std::string& runName, const std::string& pointer)
{
  value(runName, pointer); // checks that it is there
  measures_.push_back({ quantity, runName, pointer });
}

void LessonBuilder::observation(const std::string& markdown)
{
  observations_.push_back(markdown);
}

void LessonBuilder::tryNext(const std::string& why, const std::string& command)
{
  SL_CHECK_MSG(command.rfind("shadowlab ", 0) == 0, "lesson ", lesson_.name, ": not a shadowlab command: ", command);
  commands_.push_back({ why, command });
}

std::string LessonBuilder::resolutionText() const
{
  return format(settings_.resolution.x, "x", settings_.resolution.y);
}

std::string LessonBuilder::renderCommand(const std::string& name, const std::string& outDir) const
{
  const Run& source = run(name);
  std::string command;
  if (source.isReference)
  {
    command = format("shadowlab reference ", scenePath(source.spec.dataset), " -n ", settings_.referenceSamples);
  }
  else
  {
    command = "shadowlab render " + scenePath(source.spec.dataset) + " -t " + source.spec.technique;
    for (const std::string& setting : source.spec.settings)
    {
      command += " --set " + shellWord(setting);
    }
  }
  for (const std::string& sceneOverride : source.spec.sceneOverrides)
  {
    command += " --scene-set " + shellWord(sceneOverride);
  }
  return command + " -r " + resolutionText() + " --out " + shellWord(outDir);
}

std::string LessonBuilder::page() const
{
  std::ostringstream page;
  page << "# " << lesson_.title << "\n\n";
  page << "<!-- Generated by `" << settings_.command << "` from src/lessons/: edit the lesson's source, not this "
       << "page. -->\n\n";
  page << "## Question\n\n" << lesson_.question << "\n\n";

  page << "## Scene\n\n";
  for (const std::string& note : sceneNotes_)
  {
    page << note << "\n\n";
  }
  page << "| run | scene | scene overrides | technique | settings | compared with |\n"
       << "| --- | --- | --- | --- | --- | --- |\n";
  for (const std::unique_ptr<Run>& run : runs_)
  {
    const LessonRunSpec& spec = run->spec;
    page << "| `" << spec.name << "` | `" << scenePath(spec.dataset) << "` | " << codeList(spec.sceneOverrides) << " | "
         << (run->isReference ? format("ray-traced reference (Embree, ", settings_.referenceSamples, " samples)")
                              : "`" + spec.technique + "`")
         << " | " << (run->isReference ? std::string() : spec.settings.empty() ? std::string("defaults") : codeList(spec.settings))
         << " | "
         << (spec.comparedWith.empty() ? std::string() : "`" + spec.comparedWith + "`") << " |\n";
  }
  page << "\nEvery run is " << resolutionText() << " pixels. From the repository root, these commands write each run's "
       << "full output (buffers.vti, heat maps, stats.json; `shadowlab montage` reads them):\n\n```sh\n";
  for (const std::unique_ptr<Run>& run : runs_)
  {
    page << renderCommand(run->spec.name, "out/" + lesson_.name + "/" + run->spec.name) << "\n";
  }
  page << "```\n\n";

  page << "## Figures\n\n";
  for (const Figure& figure : figures_)
  {
    page << figure.caption << "\n\n![" << figure.file << "](" << figure.file << ")\n\n";
  }

  page << "## Measured\n\n"
       << "Each value is read from the run's `stats.json` (under `runs/`) at the JSON pointer (RFC 6901) in the last "
       << "column. Times are from llvmpipe on the machine that generated the page, which is shared and loaded: compare "
       << "them within this page only.\n\n"
       << "| quantity | run | value | from |\n| --- | --- | ---: | --- |\n";
  for (const Measure& measure : measures_)
  {
    const nlohmann::json& stats = run(measure.run).stats;
    page << "| " << measure.quantity << " | `" << measure.run << "` | "
         << measuredText(stats[nlohmann::json::json_pointer(measure.pointer)]) << " | `runs/" << measure.run
         << "/stats.json: " << measure.pointer << "` |\n";
  }
  page << "\n";

  if (!observations_.empty())
  {
    page << "## What the numbers say\n\n";
    for (const std::string& observation : observations_)
    {
      page << "- " << observation << "\n";
    }
    page << "\n";
  }

  page << "## Commands to try next\n\n";
  for (const Command& command : commands_)
  {
    page << "- " << command.why << "\n\n  ```sh\n  " << command.command << "\n  ```\n\n";
  }
  return page.str();
}

nlohmann::json LessonBuilder::finish()
{
  // A run whose pixels were cut short (a GL's loop cap) is not exact: the page says so in its table.
  for (const std::unique_ptr<Run>& run : runs_)
  {
    const nlohmann::json::json_pointer cutShort("/technique_statistics/cut_short_pixels");
    if (run->stats.contains(cutShort) && run->stats[cutShort].is_number() && run->stats[cutShort].get<double>() > 0.0)
    {
      measure("pixels cut short by the GL's loop cap (not exact)", run->spec.name, cutShort.to_string());
    }
  }
  writeFileChecked(dir_ / "README.md", page());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::vector<std::string> runNames;
  for (const std::unique_ptr<Run>& run : runs_)
  {
    runNames.push_back(run->spec.name);
  }
  const nlohmann::json summary = {
    { "name", lesson_.name },
    { "title", lesson_.title },
    { "question", lesson_.question },
    { "resolution", { settings_.resolution.x, settings_.resolution.y } },
    { "reference_samples", settings_.referenceSamples },
    { "command", settings_.command },
    { "seconds", seconds },
    { "runs", runNames },
  };
  writeJson(summary, dir_ / "lesson.json");
  return summary;
}

std::vector<nlohmann::json> writeLessons(const std::vector<const Lesson*>& lessons, const LessonsSettings& settings,
  const fs::path& outDir, const std::function<void(std::size_t done)>& lessonDone)
{
  ShadowRenderer renderer;
  std::vector<nlohmann::json> summaries;
  for (const Lesson* lesson : lessons)
  {
    LessonBuilder builder(*lesson, settings, renderer, outDir / lesson->name);
    lesson->build(builder);
    summaries.push_back(builder.finish());
    if (lessonDone)
    {
      lessonDone(summaries.size());
    }
  }
  writeLessonsIndex(outDir);
  return summaries;
}

void writeLessonsIndex(const fs::path& outDir)
{
  std::ostringstream index;
  index << "# Lessons\n\n"
        << "Each page asks one question about a shadow algorithm and answers it with runs made when the page was "
        << "generated: its figures are drawn from those runs' buffers and every number on it is read from a run's "
        << "`stats.json` (kept beside the page, under `runs/`), with the JSON pointer it came from. The pages are "
        << "generated by `shadowlab lessons` from src/lessons/ (one file per lesson); edit those, then regenerate.\n\n"
        << "| lesson | question | resolution | generated by | seconds |\n| --- | --- | --- | --- | ---: |\n";
  for (const Lesson& lesson : lessonRegistry())
  {
    const fs::path summaryFile = outDir / lesson.name / "lesson.json";
    std::error_code error;
    if (!fs::is_regular_file(summaryFile, error))
    {
      continue;
    }
    std::ifstream stream(summaryFile);
    const nlohmann::json summary = nlohmann::json::parse(stream, nullptr, false);
    if (summary.is_discarded() || !summary.is_object())
    {
      continue;
    }
    const nlohmann::json resolution = summary.value("resolution", nlohmann::json::array());
    char seconds[32];
    std::snprintf(seconds, sizeof(seconds), "%.0f", summary.value("seconds", 0.0));
    index << "| [" << lesson.title << "](" << lesson.name << "/README.md) | " << lesson.question << " | "
          << (resolution.size() == 2 ? format(resolution[0].dump(), "x", resolution[1].dump()) : std::string("?"))
          << " | `" << summary.value("command", std::string()) << "` | " << seconds << " |\n";
  }
  index << "\nTimes are wall seconds per lesson (rendering, ray tracing the references, drawing), on llvmpipe.\n";
  writeFileChecked(outDir / "README.md", index.str());
}

} // namespace sl
