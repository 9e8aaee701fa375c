// shadowlab differential: every technique and each of its enumerated parameter choices against the ray tracer on
// random scenes (src/differential/Differential.h), with a table per technique and, for every failed configuration,
// its seed and the one command that reproduces it.
#include "cli/Commands.h"

#include "cli/CommandProgress.h"
#include "core/Error.h"
#include "core/Parse.h"
#include "differential/Differential.h"
#include "io/OutputDirectory.h"
#include "pipeline/ShadowRenderer.h"
#include "scene/RandomScenes.h"
#include "techniques/Registry.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <iomanip>
#include <regex>
#include <sstream>

namespace sl
{
namespace
{

// "A..B" (inclusive) or "A,B,C" or "A".
std::vector<std::uint64_t> parseSeeds(const std::string& text)
{
  static const std::regex range(R"((\d{1,9})\.\.(\d{1,9}))");
  static const std::regex list(R"(\d{1,9}(,\d{1,9})*)");
  std::smatch match;
  std::vector<std::uint64_t> seeds;
  if (std::regex_match(text, match, range))
  {
    const std::uint64_t first = std::stoull(match[1]);
    const std::uint64_t last = std::stoull(match[2]);
    if (last < first || last - first >= 100000)
    {
      throw InputError("--seeds " + text + ": expected A..B with A <= B and at most 100000 seeds");
    }
    for (std::uint64_t seed = first; seed <= last; ++seed)
    {
      seeds.push_back(seed);
    }
    return seeds;
  }
  if (!std::regex_match(text, list))
  {
    throw InputError("--seeds " + text + ": expected A..B or a comma-separated list of seeds (integers)");
  }
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    seeds.push_back(std::stoull(item));
  }
  return seeds;
}

std::vector<std::string> splitComma(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ','))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

std::string percent(long long part, long long whole)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << (whole > 0 ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
  return text.str();
}

// The per-technique table (Markdown), as printed and as report.md holds it.
std::string tallyTable(const std::map<std::string, DifferentialTally>& tallies)
{
  std::ostringstream table;
  table << "| technique | configurations | unsupported or not applicable | pixels | flagged (%) | flagged beyond tolerance | ambiguous | "
           "failures | failed configurations | seconds |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& [technique, tally] : tallies)
  {
    table << "| `" << technique << "` | " << tally.configurations << " | " << tally.unsupported << " | " << tally.pixels
          << " | " << tally.flagged << " (" << percent(tally.flagged, tally.pixels) << ") | " << tally.flaggedMisses
          << " | " << tally.ambiguous << " | " << tally.failures << " | " << tally.failedConfigurations << " | "
          << std::fixed << std::setprecision(1) << tally.seconds << std::defaultfloat << " |\n";
  }
  return table.str();
}

// Per technique and flag (ConfigurationOutcome::flaggedBy): which rule excuses what, as report.md holds it.
std::string flagTable(const std::map<std::string, DifferentialTally>& tallies)
{
  std::ostringstream table;
  table << "| technique | flag | flagged (% of pixels) | flagged beyond tolerance (% of flagged) |\n"
           "| --- | --- | --- | --- |\n";
  for (const auto& [technique, tally] : tallies)
  {
    for (const auto& [name, count] : tally.flaggedBy)
    {
      table << "| `" << technique << "` | " << name << " | " << count.flagged << " ("
            << percent(count.flagged, tally.pixels) << ") | " << count.beyondTolerance << " ("
            << percent(count.beyondTolerance, count.flagged) << ") |\n";
    }
  }
  return table.str();
}

nlohmann::json outcomeJson(const ConfigurationOutcome& outcome)
{
  nlohmann::json json = { { "seed", outcome.seed }, { "technique", outcome.technique }, { "choice", outcome.choice },
    { "settings", outcome.settings }, { "scene", outcome.scene }, { "supported", outcome.supported }, { "not_applicable", outcome.notApplicable },
    { "error", outcome.error }, { "pixels", outcome.pixels }, { "flagged", outcome.flagged },
    { "flagged_beyond_tolerance", outcome.flaggedMisses }, { "ambiguous", outcome.ambiguous },
    { "failures", outcome.failures }, { "seconds", outcome.seconds }, { "command", outcome.command } };
  json["flagged_by"] = nlohmann::json::object();
  for (const auto& [name, count] : outcome.flaggedBy)
  {
    json["flagged_by"][name] = { { "flagged", count.flagged }, { "beyond_tolerance", count.beyondTolerance } };
  }
  if (outcome.worst)
  {
    json["worst"] = { { "pixel", { outcome.worst->x, outcome.worst->y } }, { "visibility", outcome.worst->visibility },
      { "reference", outcome.worst->reference }, { "allowed", outcome.worst->allowed } };
  }
  return json;
}

// How many configurations runDifferential reports for `run` (every seed: the CLI sets no seedsPerChoice): per seed,
// each technique's enumerated choices, or the one --choice. Unknown techniques are refused here as there.
std::size_t differentialConfigurationCount(const DifferentialOptions& run)
{
  std::size_t perSeed = 0;
  const auto count = [&](const TechniqueDescriptor& technique) {
    perSeed += run.choice.empty() ? enumeratedChoices(technique).size() : 1;
  };
  if (run.techniques.empty())
  {
    for (const TechniqueDescriptor& technique : techniqueRegistry())
    {
      count(technique);
    }
  }
  for (const std::string& name : run.techniques)
  {
    count(findTechnique(name));
  }
  return perSeed * run.seeds.size();
}

} // namespace

int runDifferential(const DifferentialCommandOptions& options, std::ostream& log)
{
  DifferentialOptions run;
  run.seeds = parseSeeds(options.seeds);
  run.techniques = splitComma(options.techniques);
  run.choice = options.choice;
  if (options.maxSide < 16 || options.maxSide > 1024)
  {
    throw InputError("--max-side " + std::to_string(options.maxSide) + ": must be in 16 .. 1024");
  }
  if (options.samples < 1 || options.samples > 65536)
  {
    throw InputError(options.samplesOption + " " + std::to_string(options.samples) + ": must be in 1 .. 65536");
  }
  run.maxSide = options.maxSide;
  run.referenceSamples = options.samples;
  const OutputTarget output{ options.outDir, "differential", options.force, {} };
  checkOutputTarget(output);

  const auto start = std::chrono::steady_clock::now();
  ShadowRenderer renderer;
  // Elapsed time and time left per configuration (cli/CommandProgress.h: a terminal, or --progress).
  const ProgressSwitches switches{ options.progress, options.quiet };
  const std::size_t total = differentialConfigurationCount(run);
  Progress progress("differential", format(run.seeds.size(), " seed(s), ", total, " configuration(s)"),
    "configuration", total, commandProgressStream(switches, log), commandProgressSettings(switches));
  std::size_t done = 0;
  const std::vector<ConfigurationOutcome> outcomes =
    runDifferential(renderer, run, [&](const ConfigurationOutcome& outcome) {
      progress.step(++done);
      if (outcome.failed())
      {
        log << "shadowlab: differential: FAIL " << describeFailure(outcome) << "\n";
      }
      else if (!options.quiet && !outcome.notApplicable.empty())
      {
        log << "shadowlab: differential: not applicable seed " << outcome.seed << " " << outcome.technique << " "
            << outcome.choice << ": " << outcome.notApplicable << "\n";
      }
      else if (!options.quiet && outcome.supported)
      {
        log << "shadowlab: differential: ok seed " << outcome.seed << " " << outcome.technique << " " << outcome.choice
            << ": " << outcome.pixels << " pixels, " << outcome.flagged << " flagged, " << outcome.ambiguous
            << " ambiguous (" << std::fixed << std::setprecision(1) << outcome.seconds << std::defaultfloat << " s)\n";
      }
    });
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::map<std::string, DifferentialTally> tallies = tallyByTechnique(outcomes);
  const std::string table = tallyTable(tallies);
  int failed = 0;
  for (const ConfigurationOutcome& outcome : outcomes)
  {
    failed += outcome.failed() ? 1 : 0;
  }

  writeDirectoryAtomically(output, [&](const std::filesystem::path& directory) {
    nlohmann::json json = { { "seeds", options.seeds }, { "techniques", options.techniques },
      { "choice", options.choice }, { "max_side", options.maxSide }, { "reference_samples", options.samples },
      { "seconds", seconds }, { "configurations", nlohmann::json::array() } };
    for (const ConfigurationOutcome& outcome : outcomes)
    {
      json["configurations"].push_back(outcomeJson(outcome));
    }
    writeFileChecked(directory / "differential.json", json.dump(2) + "\n");
    std::ostringstream report;
    report << table << "\nFlagged pixels by flag (each pixel under the first rule that marks it):\n\n" << flagTable(tallies)
           << "\n" << failed << " failed configuration(s) of " << outcomes.size() << "; " << std::fixed
           << std::setprecision(0) << seconds << " s wall\n";
    for (const ConfigurationOutcome& outcome : outcomes)
    {
      if (outcome.failed())
      {
        report << "\n- " << describeFailure(outcome) << "\n";
      }
    }
    writeFileChecked(directory / "report.md", report.str());
    for (const std::uint64_t seed : run.seeds)
    {
      const std::filesystem::path seedDir = directory / ("seed-" + std::to_string(seed));
      std::filesystem::create_directories(seedDir);
      writeFileChecked(seedDir / "scene.json", randomScene(seed, run.maxSide).json);
    }
  });
  log << table << "shadowlab: differential: " << failed << " failed configuration(s) of " << outcomes.size() << " ("
      << std::fixed << std::setprecision(0) << seconds << " s) -> " << printable(options.outDir.string()) << "\n";
  return failed > 0 ? 4 : 0;
}

} // namespace sl
