// What a lesson (lessons/Lesson.h) is built with: the LessonBuilder renders the runs it asks for, keeps each run's
// stats.json, draws its figures from the runs' buffers, and writes the page. Every number on a page is read from a
// run's stats.json when the page is written, and the page names where it came from:
//
//   <out>/<lesson>/README.md             the page
//   <out>/<lesson>/<figure>.png          montages (vis/Montage.h) and probe figures (probe/Probe.h)
//   <out>/<lesson>/runs/<run>/stats.json each run's stats.json: `shadowlab render`'s (output/OutputWriter.h) or
//                                        `shadowlab reference`'s, plus "scene_overrides", "settings" and, for a run
//                                        compared against another, "error" (metrics/ErrorMetrics.h metricsJson) and
//                                        "compared_with" (the other run's name); "depth_profile" where the run
//                                        asked for one (LessonRunSpec::depthProfiles)
//   <out>/<lesson>/lesson.json           name, title, resolution, the command, seconds it took
//
//
// Page sections: the question; the scene (datasets, overrides, a table of the runs and the commands that reproduce
// them); the figures; "Measured", a table whose rows are | quantity | run | value | from | with `from` =
// "`runs/<run>/stats.json: <JSON pointer>`" (RFC 6901, e.g. /buffers/kernel_texels/mean); "What the numbers say",
// sentences a lesson chooses by comparing measured values (they quote no measured value: the table has them); and
// commands to try next.
// Buffers.vti files are not kept (pages stay small); the commands rebuild them.
#pragma once

#include "core/Image.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

class ShadowRenderer;
struct Lesson;
struct NamedImage;

struct LessonsSettings
{
  glm::ivec2 resolution{ 256, 256 };
  int referenceSamples = 256;     // light samples per pixel of the ray-traced references (stratified)
  std::string command;            // the command line that generates the pages, as the page footer shows it
  std::filesystem::path datasets; // the datasets/ folder the scenes are read from
};

// One run a lesson asks for.
struct LessonRunSpec
{
  std::string name;                        // runs/<name>/, the label of its panels
  std::string dataset;                     // datasets/<dataset>/scene.json
  std::string technique;                   // a registered technique
  std::vector<std::string> settings;       // "key=value", as --set
  std::vector<std::string> sceneOverrides; // "/json/pointer=value", as --scene-set
  std::string comparedWith;                // an earlier run whose visibility is the truth here ("" = none)
  // Buffers binned over the eye's depth (metrics/DepthProfile.h, depthBins bins of equal depth ratio over the
  // binned pixels' range) into stats.json at /depth_profile/<buffer>: bins/<i>/median, ..., closed_form.
  std::vector<std::string> depthProfiles;
  int depthBins = 8;
};

// Which pixel a probe figure looks at, chosen from a run's buffers when the page is generated (never typed in):
// among the covered pixels that receive shadows, the one with the largest value of `buffer`, or with the largest
// |visibility - the compared run's visibility|; ties (within float rounding) go to the pixel nearest the centre.
struct LessonPixel
{
  enum class Rule
  {
    LargestValue,
    LargestError
  };
  Rule rule = Rule::LargestValue;
  std::string buffer;

  static LessonPixel largestValue(std::string buffer) { return { Rule::LargestValue, std::move(buffer) }; }
  static LessonPixel largestError() { return { Rule::LargestError, {} }; }
};

class LessonBuilder
{
public:
  LessonBuilder(const Lesson& lesson, const LessonsSettings& settings, ShadowRenderer& renderer,
    std::filesystem::path lessonDir);
  ~LessonBuilder();

  // Markdown paragraphs under "Scene", before the table of runs.
  void sceneNote(const std::string& markdown);

  // Renders `spec` at the lessons' resolution and writes runs/<name>/stats.json. Throws InputError for a bad spec
  // (the registry's checks), SL_CHECKs that the name is new and comparedWith names an earlier run.
  void render(const LessonRunSpec& spec);
  // The ray-traced ground truth (Embree, settings.referenceSamples stratified samples, seed 1) of a dataset.
  void reference(const std::string& name, const std::string& dataset, const std::vector<std::string>& sceneOverrides = {});

  // A montage of `buffer` over `runs` on one colour scale (vis/Montage.h), written as <stem>.png; clipQuantile and
  // signedLogLinearQuantile as MontageOptions'.
  void montage(const std::string& stem, const std::string& caption, const std::vector<std::string>& runs,
    const std::string& buffer, std::optional<double> clipQuantile = std::nullopt,
    std::optional<double> signedLogLinearQuantile = std::nullopt);
  // A montage of each run's signed visibility error (run - the run it was compared with; blue = too dark, red =
  // too bright), over the pixels covered in both.
  void errorMontage(const std::string& stem, const std::string& caption, const std::vector<std::string>& runs);

  // A probe figure (probe/Probe.h probeFigure) of one pixel of a rendered run, <stem>.png, and a `shadowlab probe`
  // command for it under "Commands to try next" (the probe's record, probe.json, is not kept: up to ~0.5 MB).
  void probe(const std::string& stem, const std::string& caption, const std::string& run, const LessonPixel& pixel);

  // A row of "Measured": the value at `pointer` in the run's stats.json (SL_CHECKed to be a number).
  void measure(const std::string& quantity, const std::string& run, const std::string& pointer);
  // The value at `pointer` in the run's stats.json, for a lesson to choose its sentences.
  double value(const std::string& run, const std::string& pointer) const;
  // A sentence of "What the numbers say" (Markdown, no numbers: the table has them).
  void observation(const std::string& markdown);
  // A command under "Commands to try next", with what it shows. `command` starts with "shadowlab ".
  void tryNext(const std::string& why, const std::string& command);
  // `shadowlab render ...` reproducing run `name` into `outDir` (at the lessons' resolution).
  std::string renderCommand(const std::string& name, const std::string& outDir) const;
  std::string resolutionText() const;

  // Writes README.md and lesson.json; returns lesson.json's content.
  nlohmann::json finish();

private:
  struct Run;
  struct Figure
  {
    std::string file;
    std::string caption;
  };
  struct Measure
  {
    std::string quantity;
    std::string run;
    std::string pointer;
  };
  struct Command
  {
    std::string why;
    std::string command;
  };

  const Run& run(const std::string& name) const;
  void addRun(std::unique_ptr<Run> run);
  std::string page() const;

  const Lesson& lesson_;
  LessonsSettings settings_;
  ShadowRenderer& renderer_;
  std::filesystem::path dir_;
  std::chrono::steady_clock::time_point start_;
  std::vector<std::string> sceneNotes_;
  std::vector<std::unique_ptr<Run>> runs_;
  std::vector<Figure> figures_;
  std::vector<Measure> measures_;
  std::vector<std::string> observations_;
  std::vector<Command> commands_;
};

// Renders every lesson of `lessons` into `outDir`/<name>/ with one renderer, and writes `outDir`/README.md listing
// the lessons found in `outDir` (those just written and any kept there). Returns each lesson's lesson.json.
// `lessonDone(n)` is called after the n-th lesson (the CLI's progress lines).
std::vector<nlohmann::json> writeLessons(const std::vector<const Lesson*>& lessons, const LessonsSettings& settings,
  const std::filesystem::path& outDir, const std::function<void(std::size_t done)>& lessonDone = {});
// `outDir`/README.md: the lessons in the registry's order that have a lesson.json in `outDir`, each with its
// question and the command that generated it.
void writeLessonsIndex(const std::filesystem::path& outDir);

} // namespace sl
