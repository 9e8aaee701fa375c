// shadowlab bench: speed against error for scenes x techniques x parameter sweeps.
//
// Every configuration runs in its own process (`shadowlab bench-run`), so a sweep can be spread over
// machines by any batch system and a crash in one configuration is reported while the rest go on. The
// ray-traced reference of each scene is computed once (`shadowlab reference`, also a child process) and
// cached under --cache, keyed by a hash of the loaded scene (geometry, lights, camera), the resolution and
// the sample count. -r takes a comma list of sizes: every configuration runs at each. Outputs (atomically, into
// --out): bench.csv, bench.json, summary.md (the renderer and the machine, then a row per configuration: time
// spread, stages, errors, memory, structures' build time, key counters; with --baseline, the error against an
// earlier bench's rows), per scene (and size, when several) stages_<scene>.png (stacked stage times),
// speed_vs_error_<scene>.png and speed_vs_penumbra_error_<scene>.png (log axes, sweeps joined and labelled),
// thumbnails_<scene>.png (visibility and error of every configuration), cost_growth_<scene>.png when a --sweep
// varies shadow_map_size, cost_growth_pixels_<scene>.png and cost_growth_pass_pixels_<scene>.png with several sizes,
// cost_growth.csv beside those, runs/<n>.json (each child's result), logs/ (a child's stdout and stderr, kept only
// when it printed something).
// Exit status: 0 when every configuration ran, 4 when some failed (their rows say why) or a reference could not
// be made (an error line says why).
#include "cli/Commands.h"

#include "cli/BenchBaseline.h"
#include "cli/BenchPlan.h"
#include "cli/CommandProgress.h"
#include "core/Error.h"
#include "core/Parse.h"
#include "io/ImageIO.h"
#include "output/OutputWriter.h"
#include "output/ParaViewScript.h"
#include "metrics/Comparison.h"
#include "metrics/DepthProfile.h"
#include "scene/Scene.h"
#include "structures/LightSpaceStructure.h"
#include "techniques/Registry.h"
#include "vis/SpeedErrorChart.h"
#include "vis/DepthProfileChart.h"
#include "vis/Montage.h"
#include "vis/StageChart.h"
#include "vis/SweepChart.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

namespace sl
{
namespace
{

struct Configuration
{
  std::size_t sceneIndex = 0;
  std::string technique;
  std::vector<std::string> settings;
  std::size_t resolutionIndex = 0; // into BenchSizes
};

// The comma-separated items of `text`; an empty item ("3,,9", "3,9,", "pcf,") is refused, naming `shown` (the
// option and its value): it is a slip, and dropping it silently would run another bench than the one typed.
std::vector<std::string> splitList(const std::string& text, const std::string& shown)
{
  std::vector<std::string> items;
  for (std::size_t start = 0;;)
  {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty())
    {
      throw InputError(shown + ": an empty item in the comma-separated list");
    }
    items.push_back(item);
    if (comma == std::string::npos)
    {
      return items;
    }
    start = comma + 1;
  }
}

// The image sizes of -r/--resolution ("128x128,256x256"): every configuration runs at each. The text of each is
// what the reference cache's key hashes, so a single size keys the cache as it always did.
struct BenchSizes
{
  std::vector<std::string> texts;
  std::vector<glm::ivec2> sizes;

  bool several() const { return texts.size() > 1; }
  // The file-name part of size `index` ("_128x128") when several are run, else "" (the names of one size's bench).
  std::string stemSuffix(std::size_t index) const { return several() ? "_" + texts[index] : std::string(); }
};

BenchSizes parseBenchSizes(const std::string& resolution)
{
  BenchSizes sizes;
  for (const std::string& text : splitList(resolution, "--resolution " + resolution))
  {
    if (std::find(sizes.texts.begin(), sizes.texts.end(), text) != sizes.texts.end())
    {
      throw InputError("--resolution " + resolution + ": " + text + " is given twice");
    }
    sizes.sizes.push_back(parseResolution(text));
    sizes.texts.push_back(text);
  }
  return sizes;
}

// FNV-1a over everything that changes the reference image.
class Hasher
{
public:
  void add(const void* data, std::size_t bytes)
  {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
    {
      hash_ = (hash_ ^ p[i]) * 1099511628211ull;
    }
  }
  template <typename T>
  void addValue(const T& value)
  {
    add(&value, sizeof(value));
  }
  std::string hex() const
  {
    std::ostringstream text;
    text << std::hex << std::setw(16) << std::setfill('0') << hash_;
    return text.str();
  }

private:
  std::uint64_t hash_ = 1469598103934665603ull;
};

std::string referenceKey(const Scene& scene, const std::string& resolution, int samples, int msaa)
{
  Hasher hasher;
  for (const SceneObject& object : scene.objects)
  {
    const TriangleMesh& mesh = object.mesh;
    hasher.add(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
    hasher.add(mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
    hasher.add(mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2));
    hasher.add(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
    hasher.add(object.alphaTexture.alpha.data.data(), object.alphaTexture.alpha.data.size() * sizeof(float));
    hasher.addValue(object.castShadows);
    hasher.addValue(object.receiveShadows);
  }
  for (const Light& light : scene.lights)
  {
    hasher.addValue(light.type);
    hasher.addValue(light.shape);
    hasher.addValue(light.center);
    hasher.addValue(light.normal);
    hasher.addValue(light.up);
    hasher.addValue(light.direction);
    hasher.addValue(light.size);
    hasher.addValue(light.coneAngleDeg);
  }
  const Camera& camera = scene.camera;
  hasher.addValue(camera.projection);
  hasher.addValue(camera.position);
  hasher.addValue(camera.focalPoint);
  hasher.addValue(camera.viewUp);
  hasher.addValue(camera.viewAngleDeg);
  hasher.addValue(camera.parallelScale);
  hasher.add(resolution.data(), resolution.size());
  hasher.addValue(samples);
  if (msaa > 1)
  {
    hasher.addValue(msaa); // single-sampled keys stay those of earlier caches
  }
  return hasher.hex();
}

struct ChildResult
{
  int exitCode = -1;
  std::string lastLine; // of its stderr
};

// Most children print nothing: their logs are kept only when they say something, and logs/ only when it
// holds a log. Best effort: an empty file or directory left behind is harmless.
void removeIfEmptyFile(const std::filesystem::path& file)
{
  std::error_code error;
  if (std::filesystem::file_size(file, error) == 0 && !error)
  {
    std::filesystem::remove(file, error);
  }
}

void removeIfEmptyDirectory(const std::filesystem::path& dir)
{
  std::error_code error;
  if (std::filesystem::is_empty(dir, error) && !error)
  {
    std::filesystem::remove(dir, error);
  }
}

// Runs this executable with `arguments`, stdout and stderr into `logFile` (removed again when empty).
ChildResult runChild(const std::vector<std::string>& arguments, const std::filesystem::path& logFile)
{
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  std::vector<std::string> all{ self };
  all.insert(all.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& argument : all)
  {
    argv.push_back(argument.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ChildResult result;
  if (spawned != 0)
  {
    removeIfEmptyFile(logFile);
    result.lastLine = "cannot start a child process";
    return result;
  }
  int status = 0;
  setForegroundChild(pid); // SIGINT/SIGTERM to bench end the child too (OutputDirectory.h)
  waitpid(pid, &status, 0);
  setForegroundChild(0);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  {
    std::ifstream log(logFile);
    for (std::string line; std::getline(log, line);)
    {
      if (!line.empty())
      {
        result.lastLine = line;
      }
    }
  }
  removeIfEmptyFile(logFile);
  if (WIFSIGNALED(status))
  {
    result.lastLine = format("crashed with signal ", WTERMSIG(status), result.lastLine.empty() ? "" : ": ", result.lastLine);
  }
  return result;
}

std::string csvField(const std::string& text)
{
  if (text.find_first_of(",\"\n") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (const char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + "\"";
}

std::string joined(const std::vector<std::string>& items, const std::string& separator)
{
  std::string text;
  for (const std::string& item : items)
  {
    text += (text.empty() ? "" : separator) + item;
  }
  return text;
}

// Why the cached reference in `dir` cannot be used (unreadable, another size, values out of range: a cache
// entry cut short or altered since it was written), or empty when it can.
std::string cachedReferenceProblem(const std::filesystem::path& dir, const glm::ivec2& resolution)
{
  const std::filesystem::path file = dir / "buffers.vti";
  if (!std::filesystem::is_regular_file(file))
  {
    return "missing";
  }
  try
  {
    const std::vector<NamedImage> buffers = readVti(file);
    for (const char* name : { "visibility", "coverage" })
    {
      const ImageF& image = requireArray(buffers, name, file.string());
      if (image.width != resolution.x || image.height != resolution.y || image.components != 1)
      {
        return format(name, " is ", image.width, "x", image.height, "x", image.components, ", not ", resolution.x,
          "x", resolution.y, "x1");
      }
      for (const float value : image.data)
      {
        if (!(value >= 0.0f && value <= 1.0f))
        {
          return format(name, " holds ", value, ", outside [0, 1]");
        }
      }
    }
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  return {};
}

// Every scene file under every combination of the --scene-sweep values, with the fixed --scene-set values.
struct SceneVariant
{
  std::string file;
  std::vector<std::string> overrides;
  std::vector<std::string> swept; // the sweep's part, for names
  Scene scene;
  std::string name;
};

// A technique parameter swept over values (--sweep key=v1,v2,...), or several parameters that take their values
// together (--sweep k1+k2=a1+a2,b1+b2,...: one configuration per tuple, e.g. warp+warp_n=psm+0,lispsm+1e6).
struct SettingSweep
{
  std::vector<std::string> keys;
  std::vector<std::vector<std::string>> values; // one tuple per configuration, a value per key
  std::string text;                             // as typed, for messages
};

std::vector<std::string> splitPlus(const std::string& text)
{
  std::vector<std::string> parts;
  for (std::size_t start = 0;;)
  {
    const std::size_t plus = text.find('+', start);
    parts.push_back(text.substr(start, plus == std::string::npos ? std::string::npos : plus - start));
    if (plus == std::string::npos)
    {
      return parts;
    }
    start = plus + 1;
  }
}

// Per-stage GPU times in bench.csv: the common stages in pipeline order, then every other stage some row ran
// (structures such as microrects, the MSAA resolve), by name; a configuration without the stage leaves its cell empty.
std::vector<std::string> stageColumns(const nlohmann::json& rows)
{
  std::vector<std::string> stages{ "gbuffer", "focus", "shadow_map", "moment_map", "summed_area_table",
    "hierarchical_shadow_map", "technique", "sublight_accumulate", "shading" };
  std::set<std::string> others;
  for (const nlohmann::json& row : rows)
  {
    if (row["status"] == "ok")
    {
      for (const auto& [stage, timing] : row["result"]["stages"].items())
      {
        if (std::find(stages.begin(), stages.end(), stage) == stages.end())
        {
          others.insert(stage);
        }
      }
    }
  }
  stages.insert(stages.end(), others.begin(), others.end());
  return stages;
}

void checkScenesRepeatAndSamples(const BenchOptions& options)
{
  if (options.sceneFiles.empty())
  {
    throw InputError("bench: no scene given");
  }
  if (options.repeat < 1)
  {
    throw InputError("--repeat " + std::to_string(options.repeat) + ": must be >= 1");
  }
  if (options.referenceSamples < 1)
  {
    throw InputError(options.referenceSamplesOption + " " + std::to_string(options.referenceSamples) + ": must be >= 1");
  }
}

// Every combination of the --scene-sweep values, each a list of "/json/pointer=value" overrides; one empty
// combination when nothing is swept.
std::vector<std::vector<std::string>> sceneSweepCombinations(const std::vector<std::string>& sceneSweeps)
{
  std::vector<std::vector<std::string>> combinations{ {} };
  for (const std::string& sweep : sceneSweeps)
  {
    const std::size_t equals = sweep.find('=');
    if (sweep.empty() || sweep[0] != '/' || equals == std::string::npos || equals + 1 == sweep.size())
    {
      throw InputError("--scene-sweep '" + sweep + "': expected /json/pointer=v1,v2,...");
    }
    std::vector<std::vector<std::string>> extended;
    for (const auto& combination : combinations)
    {
      for (const std::string& value : splitList(sweep.substr(equals + 1), "--scene-sweep " + sweep))
      {
        auto next = combination;
        next.push_back(sweep.substr(0, equals) + "=" + value);
        extended.push_back(next);
      }
    }
    combinations = extended;
  }
  return combinations;
}

// Loads every scene variant, so a bad scene or override is refused before any child runs.
std::vector<SceneVariant> loadSceneVariants(const BenchOptions& options)
{
  const std::vector<std::vector<std::string>> combinations = sceneSweepCombinations(options.sceneSweeps);
  std::vector<SceneVariant> variants;
  for (const std::string& file : options.sceneFiles)
  {
    for (const auto& combination : combinations)
    {
      SceneVariant variant;
      variant.file = file;
      variant.overrides = options.sceneOverrides;
      variant.overrides.insert(variant.overrides.end(), combination.begin(), combination.end());
      variant.swept = combination;
      variant.scene = loadScene(file, variant.overrides);
      const std::string stem = std::filesystem::path(file).parent_path().filename().string();
      variant.name = (stem.empty() ? file : stem) + (combination.empty() ? "" : " " + joined(combination, " "));
      variants.push_back(std::move(variant));
    }
  }
  return variants;
}

std::vector<std::string> selectedTechniqueNames(const std::string& techniques)
{
  if (techniques.empty())
  {
    throw InputError("--technique '" + techniques + "': no technique named");
  }
  return splitList(techniques, "--technique " + techniques);
}

std::vector<SettingSweep> parseSettingSweeps(const std::vector<std::string>& sweepTexts)
{
  std::vector<SettingSweep> sweeps;
  for (const std::string& sweep : sweepTexts)
  {
    const std::size_t equals = sweep.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == sweep.size())
    {
      throw InputError("--sweep '" + sweep + "': expected key=v1,v2,...");
    }
    SettingSweep parsed;
    parsed.text = sweep;
    parsed.keys = splitPlus(sweep.substr(0, equals));
    for (const std::string& tuple : splitList(sweep.substr(equals + 1), "--sweep " + sweep))
    {
      // A value may itself hold '+' ("1e+6") only when one key is swept.
      parsed.values.push_back(parsed.keys.size() == 1 ? std::vector<std::string>{ tuple } : splitPlus(tuple));
      if (parsed.values.back().size() != parsed.keys.size() ||
        std::any_of(parsed.keys.begin(), parsed.keys.end(), [](const std::string& key) { return key.empty(); }))
      {
        throw InputError("--sweep '" + sweep + "': '" + tuple + "' does not give one value to each of the " +
          std::to_string(parsed.keys.size()) + " keys joined by '+'");
      }
    }
    sweeps.push_back(std::move(parsed));
  }
  return sweeps;
}

// Each key must belong to at least one selected technique and be given once: a misspelt key would
// otherwise be dropped silently and the bench would run the defaults.
void checkSettingKeys(const std::vector<std::string>& settings, const std::vector<SettingSweep>& sweeps,
  const std::vector<std::string>& techniqueNames)
{
  std::set<std::string> givenKeys;
  const auto checkKey = [&](const std::string& option, const std::string& text, const std::string& key) {
    const bool known = std::any_of(techniqueNames.begin(), techniqueNames.end(),
      [&](const std::string& name) { return findTechnique(name).findParameter(key) != nullptr; });
    if (!known)
    {
      throw InputError(format(option, " ", text, ": none of the techniques ", joined(techniqueNames, ", "),
        " has a parameter '", key, "' (see shadowlab list)"));
    }
    if (!givenKeys.insert(key).second)
    {
      throw InputError(format(option, " ", text, ": ", key, " is given more than once (--set and --sweep)"));
    }
  };
  for (const std::string& setting : settings)
  {
    checkKey("--set", setting, setting.substr(0, setting.find('=')));
  }
  for (const SettingSweep& sweep : sweeps)
  {
    if (sweep.values.empty())
    {
      throw InputError("--sweep " + sweep.text + ": no values");
    }
    for (const std::string& key : sweep.keys)
    {
      checkKey("--sweep", sweep.text, key);
    }
  }
}

// The settings `technique` runs with: the --set values it declares, under every combination of the --sweep
// values it declares; each combination checked against the technique's ranges.
std::vector<std::vector<std::string>> settingCombinations(const TechniqueDescriptor& technique,
  const std::vector<std::string>& settings, const std::vector<SettingSweep>& sweeps)
{
  std::vector<std::string> base;
  for (const std::string& setting : settings)
  {
    const std::string key = setting.substr(0, setting.find('='));
    if (technique.findParameter(key))
    {
      base.push_back(setting);
    }
  }
  std::vector<std::vector<std::string>> combinations{ base };
  for (const SettingSweep& sweep : sweeps)
  {
    if (std::none_of(sweep.keys.begin(), sweep.keys.end(),
          [&](const std::string& key) { return technique.findParameter(key) != nullptr; }))
    {
      continue;
    }
    std::vector<std::vector<std::string>> extended;
    for (const auto& combination : combinations)
    {
      for (const std::vector<std::string>& tuple : sweep.values)
      {
        auto next = combination;
        for (std::size_t k = 0; k < sweep.keys.size(); ++k)
        {
          if (technique.findParameter(sweep.keys[k]))
          {
            next.push_back(sweep.keys[k] + "=" + tuple[k]);
          }
        }
        extended.push_back(next);
      }
    }
    combinations = extended;
  }
  for (const auto& combination : combinations)
  {
    ParameterValues check = technique.defaultParameters();
    for (const std::string& setting : combination)
    {
      check.set(setting);
    }
  }
  return combinations;
}

// Scene variants x image sizes x techniques x setting combinations, in the order the rows are written.
std::vector<Configuration> expandConfigurations(std::size_t variantCount, std::size_t sizeCount,
  const std::vector<std::string>& techniqueNames, const std::vector<std::string>& settings,
  const std::vector<SettingSweep>& sweeps)
{
  std::vector<Configuration> configurations;
  for (std::size_t sceneIndex = 0; sceneIndex < variantCount; ++sceneIndex)
  {
    for (std::size_t sizeIndex = 0; sizeIndex < sizeCount; ++sizeIndex)
    {
      for (const std::string& name : techniqueNames)
      {
        for (const auto& combination : settingCombinations(findTechnique(name), settings, sweeps))
        {
          configurations.push_back({ sceneIndex, name, combination, sizeIndex });
        }
      }
    }
  }
  return configurations;
}

// The scenes' files, the reference cache and the files every configuration's file parameters name are inputs:
// --out may neither hold nor replace them.
std::vector<std::filesystem::path> benchInputs(const BenchOptions& options, const std::vector<SceneVariant>& variants,
  const std::vector<Configuration>& configurations)
{
  std::vector<std::filesystem::path> inputs{ options.cacheDir };
  for (const SceneVariant& variant : variants)
  {
    const std::vector<std::filesystem::path> sceneFiles = sceneInputs(variant.scene, variant.file);
    inputs.insert(inputs.end(), sceneFiles.begin(), sceneFiles.end());
  }
  for (const Configuration& configuration : configurations)
  {
    const std::vector<std::filesystem::path> files =
      fileParameterInputs(findTechnique(configuration.technique), configuration.settings);
    inputs.insert(inputs.end(), files.begin(), files.end());
  }
  return inputs;
}

void createCacheDirectory(const std::string& cacheDir)
{
  std::error_code cacheError;
  std::filesystem::create_directories(cacheDir, cacheError);
  if (cacheError || !std::filesystem::is_directory(cacheDir))
  {
    throw InputError(format("--cache ", cacheDir, ": cannot create the directory (",
      cacheError ? cacheError.message() : "not a directory", ")"));
  }
}

// The last line of a `reference` child that failed, as the bench's user can act on it: the child's --out is the
// cache entry, named as the path it is (the user typed no such --out).
std::string referenceFailure(const ChildResult& child, const std::filesystem::path& cached)
{
  std::string line = child.lastLine.empty() ? format("exit status ", child.exitCode) : child.lastLine;
  const std::string prefix = "shadowlab: error: ";
  if (line.rfind(prefix, 0) == 0)
  {
    line = line.substr(prefix.size());
  }
  const std::string childOut = "--out " + cached.string();
  for (std::size_t at = line.find(childOut); at != std::string::npos; at = line.find(childOut, at))
  {
    line.replace(at, childOut.size(), "cache entry " + cached.string());
  }
  return line;
}

// buffers.vti of `variant`'s ray-traced reference: the cached one when it is usable, else computed into the
// cache by a `shadowlab reference` child. Empty (with an error line, counted in `failures`) when none could be
// made; the variant's configurations then run without error metrics and bench exits 4.
std::string referenceFileFor(const BenchOptions& options, const std::string& resolutionText,
  const glm::ivec2& resolution, const SceneVariant& variant, int msaa, const std::filesystem::path& logFile,
  std::ostream& log, int& failures)
{
  const std::filesystem::path cached = std::filesystem::path(options.cacheDir) /
    referenceKey(variant.scene, resolutionText, options.referenceSamples, msaa);
  // A cache entry is re-validated on every use; a bad one (cut short, altered) is computed again.
  if (const std::string problem = cachedReferenceProblem(cached, resolution); !problem.empty())
  {
    if (!options.quiet)
    {
      log << "bench: ray-traced reference of " << variant.name << " (" << resolutionText << ", "
          << options.referenceSamples << " samples"
          << (msaa > 1 ? format(", ", msaa, " per pixel") : std::string()) << ") -> " << cached.string()
          << (problem == "missing" ? std::string() : " (the cached one is unusable: " + problem + ")") << "\n";
    }
    // --force: the entry (named by its hash) belongs to the cache; a bad one is replaced, marker or not.
    std::vector<std::string> arguments{ "reference", variant.file, "--reference-samples",
      std::to_string(options.referenceSamples), "--resolution", resolutionText, "--msaa", std::to_string(msaa),
      "--out", cached.string(), "--quiet", "--force" };
    for (const std::string& override : variant.overrides)
    {
      arguments.insert(arguments.end(), { "--scene-set", override });
    }
    const ChildResult child = runChild(arguments, logFile);
    const std::string stillWrong = child.exitCode == 0 ? cachedReferenceProblem(cached, resolution) : "";
    if (child.exitCode != 0 || !stillWrong.empty())
    {
      // Said even with --quiet: the run's error columns will be empty.
      log << "bench: error: no reference for " << variant.name << ": "
          << (child.exitCode != 0 ? referenceFailure(child, cached) : cached.string() + ": " + stillWrong) << "\n";
      ++failures;
      return {};
    }
  }
  return (cached / "buffers.vti").string();
}

// The G-buffer samples per pixel a configuration renders with (TechniqueDescriptor::multisampleFor): its error is
// measured against the reference of as many samples per pixel (like for like, SS08 §7).
// A configuration whose settings do not parse is run anyway: its child fails with the message, in its row.
int multisamplesOf(const Configuration& configuration)
{
  const TechniqueDescriptor& technique = findTechnique(configuration.technique);
  ParameterValues values = technique.defaultParameters();
  try
  {
    for (const std::string& setting : configuration.settings)
    {
      values.set(setting);
    }
  }
  catch (const InputError&)
  {
    return 1;
  }
  return technique.multisampleFor(values).samples;
}

// Per scene variant and image size, by samples per pixel, the references its configurations need, before any
// configuration runs.
using ReferenceFiles = std::map<std::pair<std::size_t, std::size_t>, std::map<int, std::string>>;
ReferenceFiles prepareReferences(const BenchOptions& options, const BenchSizes& sizes,
  const std::vector<SceneVariant>& variants, const std::vector<Configuration>& configurations,
  const std::filesystem::path& logsDir, std::ostream& log, int& failures)
{
  std::map<std::pair<std::size_t, std::size_t>, std::set<int>> needed;
  for (const Configuration& configuration : configurations)
  {
    needed[{ configuration.sceneIndex, configuration.resolutionIndex }].insert(multisamplesOf(configuration));
  }
  ReferenceFiles referenceFiles;
  for (const auto& [group, samples] : needed)
  {
    const auto [s, r] = group;
    for (const int msaa : samples)
    {
      // One size keeps the log names of a one-size bench.
      const std::string stem = sizes.several() ? format("reference-", s, "-", sizes.texts[r]) : format("reference-", s);
      referenceFiles[group][msaa] = referenceFileFor(options, sizes.texts[r], sizes.sizes[r], variants[s], msaa,
        logsDir / (msaa > 1 ? format(stem, "-msaa", msaa, ".txt") : stem + ".txt"), log, failures);
    }
  }
  return referenceFiles;
}

std::vector<std::string> benchRunArguments(const BenchOptions& options, const BenchSizes& sizes,
  const SceneVariant& variant, const Configuration& configuration, const std::string& referenceFile,
  const std::filesystem::path& resultFile)
{
  std::vector<std::string> arguments{ "bench-run", variant.file, "--technique", configuration.technique,
    "--resolution", sizes.texts[configuration.resolutionIndex], "--repeat", std::to_string(options.repeat), "--result", resultFile.string() };
  if (!referenceFile.empty())
  {
    arguments.insert(arguments.end(), { "--reference", referenceFile });
  }
  for (const std::string& setting : configuration.settings)
  {
    arguments.insert(arguments.end(), { "--set", setting });
  }
  for (const std::string& override : variant.overrides)
  {
    arguments.insert(arguments.end(), { "--scene-set", override });
  }
  if (!options.depthProfile.empty())
  {
    arguments.insert(arguments.end(),
      { "--depth-profile", options.depthProfile, "--depth-bins", std::to_string(options.depthBins) });
    if (!options.depthRange.empty())
    {
      arguments.insert(arguments.end(), { "--depth-range", options.depthRange });
    }
  }
  if (!options.viewStats.empty())
  {
    arguments.insert(arguments.end(), { "--view-stats", options.viewStats });
  }
  return arguments;
}

// Whole-frame statistics of a result, one column each: those some techniques report
// (vtkSLTechniquePass::CollectStatistics) and, as <buffer>_sum, the image totals of their work counters
// (bench-run's work_counter_sums).
nlohmann::json statisticsOf(const nlohmann::json& result)
{
  nlohmann::json statistics = result.value("technique_statistics", nlohmann::json::object());
  const nlohmann::json sums = result.value("work_counter_sums", nlohmann::json::object());
  for (const auto& [name, sum] : sums.items())
  {
    statistics[name + "_sum"] = sum;
  }
  // --view-stats: <buffer>_max, _p99, _mean (a buffer no pixel tested has none).
  const nlohmann::json view = result.value("view_stats", nlohmann::json::object());
  for (const auto& [name, values] : view.items())
  {
    for (const char* key : { "max", "p99", "mean" })
    {
      if (values.contains(key))
      {
        statistics[name + "_" + key] = values[key];
      }
    }
  }
  return statistics;
}

std::string numberText(const nlohmann::json& value)
{
  std::ostringstream text;
  text << std::setprecision(6) << value.get<double>();
  return text.str();
}

// One row of bench.json: "ok" with the result in `resultFile` when `failure` is empty, else "failed" with it (a
// result that does not parse, cut short on a shared filesystem, is a failure too).
nlohmann::json configurationRow(const SceneVariant& variant, const Configuration& configuration,
  const BenchSizes& sizes, const std::filesystem::path& resultFile, const std::string& failure)
{
  nlohmann::json row = { { "scene", variant.file }, { "scene_overrides", joined(variant.overrides, " ") },
    { "scene_name", variant.name }, { "technique", configuration.technique },
    { "settings", joined(configuration.settings, " ") }, { "resolution", sizes.texts[configuration.resolutionIndex] } };
  row["status"] = "failed";
  row["error"] = failure;
  if (failure.empty())
  {
    std::ifstream file(resultFile);
    try
    {
      row["result"] = nlohmann::json::parse(file);
      row["status"] = "ok";
      row.erase("error");
    }
    catch (const nlohmann::json::exception&)
    {
      row["error"] = resultFile.string() + ": not JSON (cut short?)";
    }
  }
  return row;
}

// Runs every configuration in its own `shadowlab bench-run` child; one row of bench.json each, "ok" with the
// child's result or "failed" with its last line.
nlohmann::json runConfigurations(const BenchOptions& options, const BenchSizes& sizes,
  const std::vector<SceneVariant>& variants, const std::vector<Configuration>& configurations,
  const ReferenceFiles& referenceFiles,
  const std::filesystem::path& dir, std::ostream& log)
{
  nlohmann::json rows = nlohmann::json::array();
  // Elapsed time and time left per configuration (cli/CommandProgress.h: a terminal, or --progress).
  const ProgressSwitches switches{ options.progress, options.quiet };
  Progress progress("bench", format(configurations.size(), " configuration(s)"), "configuration",
    configurations.size(), commandProgressStream(switches, log), commandProgressSettings(switches));
  for (std::size_t c = 0; c < configurations.size(); ++c)
  {
    const Configuration& configuration = configurations[c];
    const std::filesystem::path resultFile = dir / "runs" / format(c, ".json");
    const SceneVariant& variant = variants[configuration.sceneIndex];
    const ChildResult child =
      runChild(benchRunArguments(options, sizes, variant, configuration,
                 referenceFiles.at({ configuration.sceneIndex, configuration.resolutionIndex })
                   .at(multisamplesOf(configuration)),
                 resultFile),
        dir / "logs" / format("run-", c, ".txt"));
    const bool ran = child.exitCode == 0 && std::filesystem::is_regular_file(resultFile);
    const nlohmann::json row = configurationRow(variant, configuration, sizes, resultFile,
      ran ? std::string() : child.lastLine.empty() ? format("exit status ", child.exitCode) : child.lastLine);
    // Pixels cut short (a GL's loop cap) make the row's error and time not those of the technique as written:
    // said even with --quiet.
    const double cutShort = row["status"] == "ok" ? statisticsOf(row["result"]).value("cut_short_pixels", 0.0) : 0.0;
    if (!options.quiet || cutShort > 0.0)
    {
      log << "bench: [" << (c + 1) << "/" << configurations.size() << "] " << configuration.technique << " "
          << joined(configuration.settings, " ") << " on " << variant.name
          << (sizes.several() ? " at " + sizes.texts[configuration.resolutionIndex] : std::string()) << ": "
          << (row["status"] == "ok" ? "ok" : "FAILED: " + row["error"].get<std::string>())
          << (cutShort > 0.0 ? ", warning: " + numberText(nlohmann::json(cutShort)) + " pixel(s) cut short, not exact (cut_short_pixels)" : "")
          << "\n";
    }
    rows.push_back(row);
    progress.step(c + 1);
  }
  progress.finish();
  return rows;
}

int countFailed(const nlohmann::json& rows)
{
  return static_cast<int>(
    std::count_if(rows.begin(), rows.end(), [](const nlohmann::json& row) { return row["status"] != "ok"; }));
}

std::set<std::string> statisticNamesOf(const nlohmann::json& rows)
{
  std::set<std::string> statisticNames;
  for (const nlohmann::json& row : rows)
  {
    if (row["status"] == "ok")
    {
      const nlohmann::json statistics = statisticsOf(row["result"]); // items() does not keep a temporary alive
      for (const auto& [name, value] : statistics.items())
      {
        statisticNames.insert(name);
      }
    }
  }
  return statisticNames;
}

// The number a configuration's settings give `key`, if it sets it to one.
std::optional<double> settingNumber(const std::vector<std::string>& settings, const std::string& key)
{
  for (const std::string& setting : settings)
  {
    if (setting.rfind(key + "=", 0) == 0)
    {
      return parseNumber(setting.substr(key.size() + 1));
    }
  }
  return std::nullopt;
}

// Where the bench ran: the GL renderer(s) the children report and the CPU, for summary.md, bench.json and every
// chart (llvmpipe's milliseconds are the CPU's, not a GPU's).
struct BenchEnvironment
{
  std::string renderer;  // GL_RENDERER, distinct values joined by " / " (one, unless children differed)
  std::string glVersion; // GL_VERSION (of the first ok row)
  std::string cpu;       // /proc/cpuinfo's model name
  unsigned logicalCores = 0;

  std::string line() const
  {
    return format("renderer ", renderer.empty() ? std::string("unknown") : renderer, "; machine ",
      cpu.empty() ? std::string("unknown CPU") : cpu, ", ", logicalCores, " logical cores");
  }
};

BenchEnvironment benchEnvironment(const nlohmann::json& rows)
{
  BenchEnvironment environment;
  std::vector<std::string> renderers;
  for (const nlohmann::json& row : rows)
  {
    if (row["status"] == "ok")
    {
      const std::string renderer = row["result"].value("gl_renderer", std::string());
      if (!renderer.empty() && std::find(renderers.begin(), renderers.end(), renderer) == renderers.end())
      {
        renderers.push_back(renderer);
      }
      if (environment.glVersion.empty())
      {
        environment.glVersion = row["result"].value("gl_version", std::string());
      }
    }
  }
  environment.renderer = joined(renderers, " / ");
  std::ifstream cpuInfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuInfo, line);)
  {
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
    {
      environment.cpu = line.substr(line.find(':') + 1);
      environment.cpu.erase(0, environment.cpu.find_first_not_of(" \t"));
      break;
    }
  }
  environment.logicalCores = std::thread::hardware_concurrency();
  return environment;
}

// A chart's title: what it shows, then where it was measured.
std::string benchChartTitle(const std::string& what, const BenchEnvironment& environment)
{
  return what + "\n" + environment.line();
}

// `key` of a timing object, and its _min and _max (a result without them, written before they were: the median).
double timingValue(const nlohmann::json& timing, const std::string& key)
{
  return timing.contains(key) ? timing[key].get<double>() : 0.0;
}
double timingMin(const nlohmann::json& timing, const std::string& key)
{
  return timing.contains(key + "_min") ? timing[key + "_min"].get<double>() : timingValue(timing, key);
}
double timingMax(const nlohmann::json& timing, const std::string& key)
{
  return timing.contains(key + "_max") ? timing[key + "_max"].get<double>() : timingValue(timing, key);
}

// Up to three of a result's statistics for summary.md's compact column, the rest being in bench.json and bench.csv:
// first those that say a value is not exact (cut short, flagged, fallen back, overflowed) when nonzero, then the work
// counters' image totals (<buffer>_sum), then --view-stats values, then the other nonzero counters by name; timings
// (*_ms) and byte counts (the memory column) are left to the full record.
std::string compactStatisticsText(const nlohmann::json& result)
{
  const nlohmann::json values = statisticsOf(result);
  const auto contains = [](const std::string& name, const char* part) { return name.find(part) != std::string::npos; };
  const auto rank = [&](const std::string& name, double value) -> int {
    if (value != 0.0 && (contains(name, "cut_short") || contains(name, "flag") || contains(name, "fallback") ||
                          contains(name, "overflow")))
    {
      return 0;
    }
    if (name.size() > 4 && name.compare(name.size() - 4, 4, "_sum") == 0)
    {
      return 1;
    }
    if (result.contains("view_stats") && (contains(name, "_max") || contains(name, "_p99") || contains(name, "_mean")))
    {
      return 2;
    }
    const bool timing = name.size() > 3 && name.compare(name.size() - 3, 3, "_ms") == 0;
    return value == 0.0 || timing || contains(name, "bytes") ? 4 : 3;
  };
  std::vector<std::pair<int, std::string>> ranked;
  for (const auto& [name, value] : values.items())
  {
    const int r = rank(name, value.get<double>());
    if (r < 4)
    {
      ranked.emplace_back(r, name);
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
    [](const auto& a, const auto& b) { return a.first < b.first; }); // by name within a rank (items() is sorted)
  std::string text;
  for (std::size_t i = 0; i < ranked.size() && i < 3; ++i)
  {
    text += (text.empty() ? "" : ", ") + ranked[i].second + " " + numberText(values[ranked[i].second]);
  }
  const std::size_t more = values.size() - std::min<std::size_t>(ranked.size(), 3);
  if (more > 0)
  {
    text += format(text.empty() ? "" : " ", "(+", more, " in bench.json)");
  }
  return text;
}

// "shadow_map 19.5 (71 %), technique 2.2 (8 %)": the stages, largest first, that took at least 5 % of the
// summed stage times (at most four), for summary.md; every stage is in bench.csv and stages_<scene>.png.
std::string stageShareText(const nlohmann::json& result)
{
  std::vector<std::pair<double, std::string>> stages;
  double total = 0.0;
  for (const auto& [stage, timing] : result["stages"].items())
  {
    stages.emplace_back(timingValue(timing, "gpu_ms"), stage);
    total += stages.back().first;
  }
  std::sort(stages.begin(), stages.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  for (std::size_t i = 0; i < stages.size() && i < 4; ++i)
  {
    if (total <= 0.0 || stages[i].first < 0.05 * total)
    {
      break;
    }
    std::ostringstream item;
    item << stages[i].second << " " << std::fixed << std::setprecision(1) << stages[i].first << " ("
         << std::setprecision(0) << 100.0 * stages[i].first / total << " %)";
    text += (text.empty() ? "" : ", ") + item.str();
  }
  return text;
}

double structureBytesOf(const nlohmann::json& result)
{
  return result.value("light_structure_gpu_bytes_total", 0.0);
}

// The stages of each light-space structure's build: its build passes' stage names (LightSpaceStructure.h: one timed
// stage per pass), e.g. shadow_map: focus, shadow_map. Asked of the registry, so results written before the bench
// had structure columns (a --baseline's, a plan's) get them too.
const std::map<std::string, std::vector<std::string>>& structureBuildStages()
{
  static const std::map<std::string, std::vector<std::string>> stages = [] {
    std::map<std::string, std::vector<std::string>> byStructure;
    for (const LightSpaceStructure* structure : lightSpaceStructureRegistry())
    {
      for (const vtkSmartPointer<vtkSLStagePass>& pass : structure->createBuildPasses())
      {
        byStructure[structure->name].push_back(pass->GetStageName());
      }
    }
    return byStructure;
  }();
  return stages;
}

// One light-space structure a configuration built: the summed median GPU times of its build stages and its bytes.
struct StructureCost
{
  std::string name;
  double buildMs = 0.0;
  double bytes = 0.0;
};

// Every structure the result built (its light_structure_gpu_bytes), in registry (build) order. A stage two of them
// share (the dual MSSM is built by the HSM's pass) is counted for the first only, so the costs sum to the time
// the structures took.
std::vector<StructureCost> structureCostsOf(const nlohmann::json& result)
{
  const nlohmann::json bytes = result.value("light_structure_gpu_bytes", nlohmann::json::object());
  const nlohmann::json stages = result.value("stages", nlohmann::json::object());
  std::vector<StructureCost> costs;
  std::set<std::string> counted;
  for (const LightSpaceStructure* structure : lightSpaceStructureRegistry())
  {
    if (!bytes.contains(structure->name))
    {
      continue;
    }
    StructureCost cost{ structure->name, 0.0, bytes[structure->name].get<double>() };
    const auto known = structureBuildStages().find(structure->name);
    for (const std::string& stage : known == structureBuildStages().end() ? std::vector<std::string>{} : known->second)
    {
      if (stages.contains(stage) && counted.insert(stage).second)
      {
        cost.buildMs += timingValue(stages[stage], "gpu_ms");
      }
    }
    costs.push_back(cost);
  }
  return costs;
}

// The structure names any ok row built, in registry order: one bench.csv column pair each.
std::vector<std::string> structureColumns(const nlohmann::json& rows)
{
  std::set<std::string> built;
  for (const nlohmann::json& row : rows)
  {
    if (row["status"] == "ok")
    {
      for (const StructureCost& cost : structureCostsOf(row["result"]))
      {
        built.insert(cost.name);
      }
    }
  }
  std::vector<std::string> names;
  for (const LightSpaceStructure* structure : lightSpaceStructureRegistry())
  {
    if (built.count(structure->name))
    {
      names.push_back(structure->name);
    }
  }
  return names;
}

// "24.1 (71 %): shadow_map 19.5 (57 %)": every structure's build time and its share of the frame's median GPU time,
// then the largest structure's; "-" when none was built.
double totalBuildMs(const std::vector<StructureCost>& costs)
{
  double total = 0.0;
  for (const StructureCost& cost : costs)
  {
    total += cost.buildMs;
  }
  return total;
}

std::string structureShareText(const nlohmann::json& result)
{
  const std::vector<StructureCost> costs = structureCostsOf(result);
  if (costs.empty())
  {
    return "-";
  }
  double total = 0.0;
  const StructureCost* largest = &costs.front();
  for (const StructureCost& cost : costs)
  {
    total += cost.buildMs;
    largest = cost.buildMs > largest->buildMs ? &cost : largest;
  }
  const double frame = timingValue(result, "frame_gpu_ms");
  const auto share = [&](double ms) { return frame > 0.0 ? format(" (", std::lround(100.0 * ms / frame), " %)") : ""; };
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << total << share(total) << ": " << largest->name << " "
       << largest->buildMs << share(largest->buildMs);
  return text.str();
}

// bench-run's warm frames (median, min, max GPU ms of frames that reuse unchanged structures), when it wrote them:
// warm_frame_gpu_ms with _min and _max beside it as the frame's own spread is written, or one object
// {median, min, max}.
std::optional<std::array<double, 3>> warmFrameOf(const nlohmann::json& result)
{
  const nlohmann::json warm = result.value("warm_frame_gpu_ms", nlohmann::json());
  if (warm.is_number())
  {
    const double median = warm.get<double>();
    return std::array<double, 3>{ median, result.value("warm_frame_gpu_ms_min", median),
      result.value("warm_frame_gpu_ms_max", median) };
  }
  if (!warm.is_object() || !warm.contains("median") || !warm["median"].is_number())
  {
    return std::nullopt;
  }
  const double median = warm["median"].get<double>();
  return std::array<double, 3>{ median, warm.value("min", median), warm.value("max", median) };
}

bool anyWarmFrame(const nlohmann::json& rows)
{
  return std::any_of(rows.begin(), rows.end(),
    [](const nlohmann::json& row) { return row["status"] == "ok" && warmFrameOf(row["result"]).has_value(); });
}

// A shadow-map size as a cell: the number, or the word a choice holds ("auto").
std::string parameterText(const nlohmann::json& value)
{
  return value.is_number() ? numberText(value) : value.is_string() ? value.get<std::string>() : std::string();
}

// The map size the frame rendered, given or chosen under shadow_map_size=auto (bench-run's and stats.json's
// shadow_map_size_chosen), where the result has it.
std::string chosenMapSizeText(const nlohmann::json& result)
{
  if (result.contains("shadow_map_size_chosen"))
  {
    return parameterText(result["shadow_map_size_chosen"]);
  }
  return parameterText(
    result.value("technique_statistics", nlohmann::json::object()).value("shadow_map_size_chosen", nlohmann::json()));
}

// --baseline: this run's rows matched with the baseline's (cli/BenchBaseline.h), one entry per row.
struct BaselineMatch
{
  std::string problem; // "no baseline row", "2 baseline rows match", "failed here", "no error metrics here"
  BaselineRow baseline;
  double rmse = 0.0;
  bool worse = false;
};

std::vector<BaselineMatch> matchBaseline(const nlohmann::json& rows, const BenchBaseline& baseline)
{
  std::vector<BaselineSettingsOf> settings;
  for (const nlohmann::json& row : rows)
  {
    settings.push_back({ row["technique"].get<std::string>(), row["settings"].get<std::string>() });
  }
  const std::vector<std::string> distinguishing = distinguishingSettings(settings);
  std::vector<BaselineMatch> matches;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    BaselineMatch match;
    const std::string key = benchBaselineKey(row["technique"], row["scene"], row["scene_overrides"],
      row["resolution"], distinguishing[c]);
    // The distinguishing settings first, then all of them (a run sweeping a value its baseline set for every row).
    const std::vector<BaselineRow>* candidates = nullptr;
    if (const auto found = baseline.rowsByKey.find(key); found != baseline.rowsByKey.end())
    {
      candidates = &found->second;
    }
    else if (const auto full = baseline.rowsByFullKey.find(benchBaselineKey(row["technique"], row["scene"],
               row["scene_overrides"], row["resolution"], sortedSettings(row["settings"])));
             full != baseline.rowsByFullKey.end())
    {
      candidates = &full->second;
    }
    if (!candidates)
    {
      match.problem = "no baseline row";
    }
    else if (candidates->size() > 1)
    {
      match.problem = format(candidates->size(), " baseline rows match");
    }
    else if (row["status"] != "ok")
    {
      match.problem = "failed here";
    }
    else if (!row["result"].contains("error"))
    {
      match.problem = "no error metrics here";
    }
    else
    {
      match.baseline = candidates->front();
      // Both as bench.csv prints them (6 significant digits): an identical re-run differs by 0, not by the rounding.
      match.rmse = parseNumber(numberText(row["result"]["error"]["covered"]["rmse"])).value();
      match.worse = baselineWorse(match.rmse, match.baseline.rmse);
    }
    matches.push_back(match);
  }
  return matches;
}

// The error columns of bench.csv, in order, with where each comes from in a result's "error".
struct ErrorColumn
{
  const char* header;
  const char* set; // "covered" or "penumbra"
  const char* key;
};
const std::vector<ErrorColumn>& benchErrorColumns()
{
  static const std::vector<ErrorColumn> columns{ { "rmse", "covered", "rmse" }, { "mae", "covered", "mae" },
    { "max_abs_error", "covered", "max_abs_error" }, { "fraction_above_0.05", "covered", "fraction_above_0.05" },
    { "p99_abs_error", "covered", "p99_abs_error" }, { "penumbra_rmse", "penumbra", "rmse" },
    { "penumbra_p99_abs_error", "penumbra", "p99_abs_error" },
    { "penumbra_fraction_above_0.05", "penumbra", "fraction_above_0.05" }, { "penumbra_pixels", "penumbra", "pixels" } };
  return columns;
}

// bench.csv: a row per configuration. `baseline` (--baseline): a match per row, adding baseline_rmse and rmse_delta.
std::string benchCsv(const nlohmann::json& rows, const std::set<std::string>& statisticNames,
  const std::vector<BaselineMatch>* baseline)
{
  const std::vector<std::string> stages = stageColumns(rows);
  const std::vector<std::string> structures = structureColumns(rows);
  const bool warm = anyWarmFrame(rows);
  std::vector<std::string> header{ "scene", "scene_overrides", "technique", "settings", "resolution", "status",
    "frame_gpu_ms", "frame_gpu_ms_min", "frame_gpu_ms_max", "frame_wall_ms", "frame_wall_ms_min", "frame_wall_ms_max" };
  if (warm)
  {
    header.insert(header.end(), { "warm_frame_gpu_ms", "warm_frame_gpu_ms_min", "warm_frame_gpu_ms_max" });
  }
  for (const std::string& stage : stages)
  {
    for (const char* suffix : { "_gpu_ms", "_gpu_ms_min", "_gpu_ms_max" })
    {
      header.push_back(stage + suffix);
    }
  }
  header.push_back("light_structure_gpu_bytes");
  header.push_back("structures_build_gpu_ms");
  for (const std::string& structure : structures)
  {
    header.insert(header.end(), { structure + "_build_gpu_ms", structure + "_gpu_bytes" });
  }
  header.insert(header.end(), statisticNames.begin(), statisticNames.end());
  for (const ErrorColumn& column : benchErrorColumns())
  {
    header.push_back(column.header);
  }
  if (baseline)
  {
    header.insert(header.end(), { "baseline_rmse", "rmse_delta" });
  }
  header.insert(header.end(), { "renderer", "error" });
  std::ostringstream csv;
  csv << joined(header, ",") << "\n";
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    const nlohmann::json& row = rows[r];
    std::vector<std::string> cells{ csvField(row["scene"]), csvField(row["scene_overrides"]),
      row["technique"].get<std::string>(), csvField(row["settings"]), row["resolution"].get<std::string>(),
      row["status"].get<std::string>() };
    if (row["status"] != "ok")
    {
      cells.resize(header.size() - 1);
      cells.push_back(csvField(row["error"]));
      csv << joined(cells, ",") << "\n";
      continue;
    }
    const nlohmann::json& result = row["result"];
    const auto number = [](double value) { return numberText(nlohmann::json(value)); };
    for (const char* key : { "frame_gpu_ms", "frame_wall_ms" })
    {
      cells.insert(cells.end(),
        { number(timingValue(result, key)), number(timingMin(result, key)), number(timingMax(result, key)) });
    }
    if (warm)
    {
      const auto warmFrame = warmFrameOf(result);
      for (std::size_t k = 0; k < 3; ++k)
      {
        cells.push_back(warmFrame ? number((*warmFrame)[k]) : "");
      }
    }
    for (const std::string& stage : stages)
    {
      const bool ran = result["stages"].contains(stage);
      const nlohmann::json timing = ran ? result["stages"][stage] : nlohmann::json::object();
      cells.insert(cells.end(), { ran ? number(timingValue(timing, "gpu_ms")) : "",
        ran ? number(timingMin(timing, "gpu_ms")) : "", ran ? number(timingMax(timing, "gpu_ms")) : "" });
    }
    cells.push_back(format(static_cast<unsigned long long>(structureBytesOf(result))));
    const std::vector<StructureCost> costs = structureCostsOf(result);
    cells.push_back(number(totalBuildMs(costs)));
    for (const std::string& structure : structures)
    {
      const auto cost = std::find_if(
        costs.begin(), costs.end(), [&](const StructureCost& item) { return item.name == structure; });
      cells.push_back(cost == costs.end() ? "" : number(cost->buildMs));
      cells.push_back(cost == costs.end() ? "" : format(static_cast<unsigned long long>(cost->bytes)));
    }
    const nlohmann::json statistics = statisticsOf(result);
    for (const std::string& name : statisticNames)
    {
      cells.push_back(statistics.contains(name) ? numberText(statistics[name]) : "");
    }
    for (const ErrorColumn& column : benchErrorColumns())
    {
      const bool has = result.contains("error") && result["error"][column.set].contains(column.key);
      cells.push_back(has ? numberText(result["error"][column.set][column.key]) : "");
    }
    if (baseline)
    {
      const BaselineMatch& match = (*baseline)[r];
      cells.push_back(match.problem.empty() ? number(match.baseline.rmse) : "");
      cells.push_back(match.problem.empty() ? number(match.rmse - match.baseline.rmse) : "");
    }
    cells.push_back(csvField(result.value("gl_renderer", std::string())));
    cells.push_back(result.contains("error") ? "" : "no reference");
    csv << joined(cells, ",") << "\n";
  }
  return csv.str();
}

// summary.md's "error against the baseline" table (--baseline), with the rule it applies.
std::string baselineMarkdown(const nlohmann::json& rows, const std::vector<BaselineMatch>& matches,
  const BenchBaseline& baseline, int referenceSamples)
{
  std::ostringstream markdown;
  const std::size_t worse = static_cast<std::size_t>(
    std::count_if(matches.begin(), matches.end(), [](const BaselineMatch& match) { return match.worse; }));
  const std::size_t compared = static_cast<std::size_t>(
    std::count_if(matches.begin(), matches.end(), [](const BaselineMatch& match) { return match.problem.empty(); }));
  markdown << "\n## Error against the baseline\n\n"
           << "Baseline: " << baseline.dir << " (" << baseline.rowCount << " rows with errors). Rows are matched by "
           << "technique, scene file, scene overrides, resolution and the settings that tell a technique's "
           << "configurations apart (those not common to all its rows in the same bench), else by all settings. Rule: "
           << baselineRuleText() << ". " << worse << " of " << compared << " compared configuration(s) worse."
           << (baseline.referenceSamples > 0 && baseline.referenceSamples != referenceSamples
                  ? format(" The baseline's references have ", baseline.referenceSamples, " samples, this run's ",
                      referenceSamples, ": an RMSE change then includes the references' own noise (compare at equal "
                      "--reference-samples).")
                  : std::string())
           << "\n\n"
           << "| scene | technique | settings | size | baseline settings | RMSE | baseline RMSE | RMSE change | "
              "penumbra RMSE | baseline penumbra RMSE | p99 error | baseline p99 | worse |\n"
           << "| --- | --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
  const auto optionalCell = [](const std::optional<double>& value) {
    return value ? numberText(nlohmann::json(*value)) : std::string("-");
  };
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    const nlohmann::json& row = rows[r];
    const BaselineMatch& match = matches[r];
    markdown << "| " << row["scene_name"].get<std::string>() << " | " << row["technique"].get<std::string>() << " | "
             << row["settings"].get<std::string>() << " | " << row["resolution"].get<std::string>() << " | ";
    if (!match.problem.empty())
    {
      markdown << match.problem << " | | | | | | | | |\n";
      continue;
    }
    markdown << match.baseline.settings << " | ";
    const nlohmann::json& error = row["result"]["error"];
    const std::optional<double> penumbra = error["penumbra"].value("pixels", 0.0) > 0.0
      ? std::optional<double>(error["penumbra"]["rmse"].get<double>())
      : std::nullopt;
    markdown << numberText(nlohmann::json(match.rmse)) << " | " << numberText(nlohmann::json(match.baseline.rmse))
             << " | " << (match.rmse > match.baseline.rmse ? "+" : "")
             << numberText(nlohmann::json(match.rmse - match.baseline.rmse)) << " | " << optionalCell(penumbra) << " | " << optionalCell(match.baseline.penumbraRmse) << " | "
             << numberText(error["covered"]["p99_abs_error"]) << " | " << optionalCell(match.baseline.p99AbsError)
             << " | " << (match.worse ? "**worse**" : "no") << " |\n";
  }
  return markdown.str();
}

std::string summaryMarkdown(const nlohmann::json& rows, const BenchOptions& options, const BenchSizes& sizes,
  const BenchEnvironment& environment, const std::vector<std::string>& chartFiles, const std::string& moreSections)
{
  const bool warm = anyWarmFrame(rows);
  std::ostringstream markdown;
  markdown << "Renderer: " << (environment.renderer.empty() ? std::string("unknown") : environment.renderer)
           << (environment.glVersion.empty() ? std::string() : ", OpenGL " + environment.glVersion) << ".  \n"
           << "Machine: " << (environment.cpu.empty() ? std::string("unknown CPU") : environment.cpu) << ", "
           << environment.logicalCores << " logical cores.  \n"
           << (sizes.several() ? "Resolutions " : "Resolution ") << joined(sizes.texts, ", ")
           << "; times are the median (min-max) of " << options.repeat
           << " timed frame(s) after one warm-up; errors are of visibility against a " << options.referenceSamples
           << "-sample ray-traced reference over covered pixels, the penumbra being the pixels whose reference is "
              "strictly between 0 and 1; p99 is the 99th percentile of |error|, > 0.05 the share of pixels off by more "
              "than 0.05. Structures: GPU memory of the light-space structures built, and the GPU time of their build stages, "
              "all structures (share of the frame's median): the largest one (share); per structure in bench.csv. "
           << (warm ? "Warm frame: the median (min-max) of frames that reuse the structures while light and casters "
                      "are unchanged. "
                    : "")
           << "Statistics: at most three key counters; every counter is in bench.json and bench.csv.\n\n";
  markdown << "| scene | technique | settings | " << (sizes.several() ? "size | " : "") << "GPU ms median (min-max) | "
           << (warm ? "warm frame ms | " : "")
           << "largest stages, GPU ms (share) | wall ms | RMSE | penumbra RMSE | p99 error | penumbra p99 | > 0.05 | "
              "max error | structures MiB | structures ms (share of frame) | statistics |\n"
           << "| --- | --- | --- | " << (sizes.several() ? "--- | " : "") << "---: | " << (warm ? "---: | " : "")
           << "--- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |\n";
  for (const nlohmann::json& row : rows)
  {
    markdown << "| " << row["scene_name"].get<std::string>() << " | " << row["technique"].get<std::string>() << " | "
             << row["settings"].get<std::string>() << " | "
             << (sizes.several() ? row["resolution"].get<std::string>() + " | " : std::string());
    if (row["status"] != "ok")
    {
      markdown << "failed: " << row["error"].get<std::string>() << (warm ? " |" : "") << " | | | | | | | | | | | |\n";
      continue;
    }
    const nlohmann::json& result = row["result"];
    const bool hasError = result.contains("error");
    const auto errorCell = [&](const char* set, const char* key) {
      return hasError && result["error"][set].contains(key) ? numberText(result["error"][set][key]) : std::string("-");
    };
    std::ostringstream time;
    time << std::fixed << std::setprecision(2) << timingValue(result, "frame_gpu_ms") << " ("
         << timingMin(result, "frame_gpu_ms") << "-" << timingMax(result, "frame_gpu_ms") << ")";
    std::ostringstream wall;
    wall << std::fixed << std::setprecision(2) << timingValue(result, "frame_wall_ms");
    std::ostringstream bytes;
    bytes << std::fixed << std::setprecision(2) << structureBytesOf(result) / (1024.0 * 1024.0);
    std::string warmCell;
    if (warm)
    {
      const auto warmFrame = warmFrameOf(result);
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(2);
      if (warmFrame)
      {
        cell << (*warmFrame)[0] << " (" << (*warmFrame)[1] << "-" << (*warmFrame)[2] << ")";
      }
      warmCell = (warmFrame ? cell.str() : std::string("-")) + " | ";
    }
    markdown << time.str() << " | " << warmCell << stageShareText(result) << " | "
             << wall.str() << " | " << errorCell("covered", "rmse") << " | " << errorCell("penumbra", "rmse") << " | "
             << errorCell("covered", "p99_abs_error") << " | " << errorCell("penumbra", "p99_abs_error") << " | "
             << errorCell("covered", "fraction_above_0.05") << " | " << errorCell("covered", "max_abs_error") << " | "
             << bytes.str() << " | " << structureShareText(result) << " | " << compactStatisticsText(result) << " |\n";
  }
  markdown << moreSections; // cost growth against image size, error against the baseline
  if (!chartFiles.empty())
  {
    markdown << "\nCharts:\n\n";
    for (const std::string& file : chartFiles)
    {
      markdown << "- [" << file << "](" << file << ")\n";
    }
  }
  return markdown.str();
}

// The file-name stem of a scene variant: its dataset folder, then each swept scene value.
std::string variantStem(const SceneVariant& variant, std::size_t sceneIndex)
{
  std::string stem = std::filesystem::path(variant.file).parent_path().filename().string();
  stem = stem.empty() ? std::to_string(sceneIndex) : stem;
  for (const std::string& swept : variant.swept)
  {
    std::string part = swept;
    for (char& c : part)
    {
      c = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
    }
    stem += "_" + part;
  }
  return stem;
}

// The keys some --sweep varies.
std::set<std::string> sweptKeys(const std::vector<SettingSweep>& sweeps)
{
  std::set<std::string> keys;
  for (const SettingSweep& sweep : sweeps)
  {
    keys.insert(sweep.keys.begin(), sweep.keys.end());
  }
  return keys;
}

// A configuration's series on the charts (technique and the settings no sweep varies) and its point's label (the
// swept values, space-separated; empty when nothing is swept).
std::pair<std::string, std::string> seriesAndLabel(const Configuration& configuration, const std::set<std::string>& swept)
{
  std::string series = configuration.technique;
  std::string label;
  std::string labelKeys;
  for (const std::string& setting : configuration.settings)
  {
    const std::size_t equals = setting.find('=');
    if (swept.count(setting.substr(0, equals)))
    {
      label += (label.empty() ? "" : " ") + setting.substr(equals + 1);
      labelKeys += (labelKeys.empty() ? "" : " ") + setting.substr(0, equals);
    }
    else
    {
      series += " " + setting;
    }
  }
  // The legend names what the point labels are: "pcf, labels: kernel_texels".
  return { labelKeys.empty() ? series : series + ", labels: " + labelKeys, label };
}

// A chart of one scene variant at one image size: (scene index, size index).
using ChartGroup = std::pair<std::size_t, std::size_t>;
ChartGroup chartGroupOf(const Configuration& configuration)
{
  return { configuration.sceneIndex, configuration.resolutionIndex };
}

// The file-name stem of a chart group: the variant's, with the size when several are run ("planar-occluder_128x128").
std::string chartGroupStem(const std::vector<SceneVariant>& variants, const BenchSizes& sizes, const ChartGroup& group)
{
  return variantStem(variants[group.first], group.first) + sizes.stemSuffix(group.second);
}

// speed_vs_error_<scene>.png (RMSE) and, where the reference has a penumbra, speed_vs_penumbra_error_<scene>.png: one
// per scene variant with error metrics; one series per technique and fixed settings, a sweep's configurations being
// its points, joined and labelled by their swept values.
std::vector<std::string> writeSpeedErrorCharts(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const std::vector<SettingSweep>& sweeps, const BenchSizes& sizes,
  const BenchEnvironment& environment, const std::filesystem::path& dir)
{
  const std::set<std::string> swept = sweptKeys(sweeps);
  std::map<ChartGroup, std::vector<ChartPoint>> chartPoints;
  std::map<ChartGroup, std::vector<ChartPoint>> penumbraPoints;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    if (row["status"] == "ok" && row["result"].contains("error"))
    {
      const nlohmann::json& result = row["result"];
      const auto [series, label] = seriesAndLabel(configurations[c], swept);
      const double time = result["frame_gpu_ms"].get<double>();
      chartPoints[chartGroupOf(configurations[c])].push_back(
        { series, time, result["error"]["covered"]["rmse"].get<double>(), label });
      if (result["error"]["penumbra"]["pixels"].get<std::size_t>() > 0)
      {
        penumbraPoints[chartGroupOf(configurations[c])].push_back(
          { series, time, result["error"]["penumbra"]["rmse"].get<double>(), label });
      }
    }
  }
  std::vector<std::string> files;
  for (const auto& [group, points] : chartPoints)
  {
    const SceneVariant& variant = variants[group.first];
    const std::string& resolution = sizes.texts[group.second];
    const std::string stem = chartGroupStem(variants, sizes, group);
    files.push_back("speed_vs_error_" + stem + ".png");
    writeSpeedErrorChart(points,
      benchChartTitle("speed vs error: " + variant.name + " (" + resolution + ")", environment), dir / files.back());
    if (penumbraPoints.count(group))
    {
      files.push_back("speed_vs_penumbra_error_" + stem + ".png");
      SpeedErrorAxes axes;
      axes.errorTitle = "penumbra RMSE (reference strictly inside (0, 1))";
      writeSpeedErrorChart(penumbraPoints.at(group),
        benchChartTitle("speed vs penumbra error: " + variant.name + " (" + resolution + ")", environment),
        dir / files.back(), axes);
    }
  }
  return files;
}

// stages_<scene>.png: per scene variant, a bar per configuration stacked from its stages' median GPU times.
std::vector<std::string> writeStageCharts(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchSizes& sizes, const BenchEnvironment& environment,
  const std::filesystem::path& dir)
{
  const std::vector<std::string> allStages = stageColumns(rows);
  std::map<ChartGroup, std::vector<std::size_t>> byVariant;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    if (rows[c]["status"] == "ok")
    {
      byVariant[chartGroupOf(configurations[c])].push_back(c);
    }
  }
  std::vector<std::string> files;
  for (const auto& [group, indices] : byVariant)
  {
    StageChartSpec spec;
    for (const std::string& stage : allStages)
    {
      if (std::any_of(indices.begin(), indices.end(),
            [&](std::size_t c) { return rows[c]["result"]["stages"].contains(stage); }))
      {
        spec.stages.push_back(stage);
      }
    }
    std::vector<StageBar> bars;
    for (const std::size_t c : indices)
    {
      const nlohmann::json& result = rows[c]["result"];
      std::ostringstream label;
      label << rows[c]["technique"].get<std::string>()
            << (rows[c]["settings"].get<std::string>().empty() ? "" : " " + rows[c]["settings"].get<std::string>())
            << "  " << std::fixed << std::setprecision(1) << timingValue(result, "frame_gpu_ms") << " ms ("
            << timingMin(result, "frame_gpu_ms") << "-" << timingMax(result, "frame_gpu_ms") << ")";
      StageBar bar{ label.str(), {} };
      for (const std::string& stage : spec.stages)
      {
        bar.stageMs.push_back(result["stages"].contains(stage) ? timingValue(result["stages"][stage], "gpu_ms") : 0.0);
      }
      bars.push_back(bar);
    }
    const SceneVariant& variant = variants[group.first];
    spec.title = benchChartTitle(
      "GPU time by stage: " + variant.name + " (" + sizes.texts[group.second] + "; label: frame median (min-max))",
      environment);
    files.push_back("stages_" + chartGroupStem(variants, sizes, group) + ".png");
    writeStageChart(bars, spec, dir / files.back());
  }
  return files;
}

// The side-by-side of two montages: `top` above `bottom`, on white, left-aligned.
ImageU8 stackImages(const ImageU8& top, const ImageU8& bottom)
{
  ImageU8 stacked(std::max(top.width, bottom.width), top.height + bottom.height, 3, 255);
  const auto place = [&](const ImageU8& image, int rowOffset) {
    for (int y = 0; y < image.height; ++y)
    {
      std::copy_n(&image.data[static_cast<std::size_t>(y) * image.width * 3], static_cast<std::size_t>(image.width) * 3,
        &stacked.data[(static_cast<std::size_t>(y + rowOffset) * stacked.width) * 3]);
    }
  };
  place(bottom, 0); // row 0 at the bottom
  place(top, bottom.height);
  return stacked;
}

// thumbnails_<scene>.png: per scene variant, the reference and each configuration's visibility (one scale) above each
// configuration's error against the reference (one signed scale), from the children's <n>.thumbnail.vti, which are
// removed afterwards (they are the strip's inputs, not results).
std::vector<std::string> writeThumbnailStrips(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchSizes& sizes, const BenchEnvironment& environment,
  const std::filesystem::path& dir)
{
  std::map<ChartGroup, std::vector<MontagePanel>> visibilityPanels;
  std::map<ChartGroup, std::vector<MontagePanel>> errorPanels;
  const auto maskOf = [](const ImageF& mask) {
    ImageU8 valid(mask.width, mask.height, 1, 0);
    for (std::size_t i = 0; i < mask.pixelCount(); ++i)
    {
      valid.data[i] = mask.data[i] > 0.5f ? 255 : 0;
    }
    return valid;
  };
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const std::filesystem::path file = dir / "runs" / format(c, ".thumbnail.vti");
    if (rows[c]["status"] != "ok" || !std::filesystem::is_regular_file(file))
    {
      continue;
    }
    const std::vector<NamedImage> thumbnails = readVti(file);
    const ChartGroup sceneIndex = chartGroupOf(configurations[c]);
    const nlohmann::json& result = rows[c]["result"];
    std::vector<std::string> labels{ rows[c]["technique"].get<std::string>() };
    for (const std::string& setting : configurations[c].settings)
    {
      labels.push_back(setting);
    }
    const NamedImage* reference = findNamed(thumbnails, "reference");
    if (reference && visibilityPanels[sceneIndex].empty())
    {
      visibilityPanels[sceneIndex].push_back(
        { reference->image, maskOf(requireArray(thumbnails, "reference_mask", file.string())), { "reference" } });
    }
    std::vector<std::string> visibilityLabels = labels;
    if (result.contains("error"))
    {
      visibilityLabels.push_back("RMSE " + numberText(result["error"]["covered"]["rmse"]));
    }
    visibilityPanels[sceneIndex].push_back({ requireArray(thumbnails, "visibility", file.string()),
      maskOf(requireArray(thumbnails, "visibility_mask", file.string())), visibilityLabels });
    if (const NamedImage* error = findNamed(thumbnails, "error"))
    {
      std::vector<std::string> errorLabels = labels;
      if (result.contains("error"))
      {
        errorLabels.push_back("p99 " + numberText(result["error"]["covered"]["p99_abs_error"]));
      }
      errorPanels[sceneIndex].push_back(
        { error->image, maskOf(requireArray(thumbnails, "error_mask", file.string())), errorLabels });
    }
  }
  std::vector<std::string> files;
  for (const auto& [sceneIndex, panels] : visibilityPanels)
  {
    const SceneVariant& variant = variants[sceneIndex.first];
    MontageOptions visibility;
    visibility.title =
      "visibility: " + variant.name + " (" + sizes.texts[sceneIndex.second] + ", thumbnails) - " + environment.renderer;
    ImageU8 strip = renderMontage(panels, visibility);
    if (errorPanels.count(sceneIndex))
    {
      MontageOptions error;
      error.title = "error (technique - reference)";
      error.kind = BufferKind::Signed;
      strip = stackImages(strip, renderMontage(errorPanels.at(sceneIndex), error));
    }
    files.push_back("thumbnails_" + chartGroupStem(variants, sizes, sceneIndex) + ".png");
    writePng(dir / files.back(), strip);
  }
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    std::error_code ignored;
    std::filesystem::remove(dir / "runs" / format(c, ".thumbnail.vti"), ignored);
  }
  return files;
}

// A guide line through `anchor` growing as the x value to `power` up to `largestX`, named so that it sorts last in the
// legend ("~"): against it a series' slope reads off how the cost grows.
void addGrowthGuide(std::vector<SweepPoint>& points, const std::string& name, double power)
{
  const SweepPoint anchor = *std::min_element(points.begin(), points.end(),
    [](const SweepPoint& a, const SweepPoint& b) { return a.parameter < b.parameter; });
  double largestX = anchor.parameter;
  for (const SweepPoint& point : points)
  {
    largestX = std::max(largestX, point.parameter);
  }
  const std::string guide = "~ " + name + ", from " + anchor.series;
  points.push_back({ guide, anchor.parameter, anchor.value });
  points.push_back({ guide, largestX, anchor.value * std::pow(largestX / anchor.parameter, power) });
}

void dropNonPositive(std::vector<SweepPoint>& points)
{
  points.erase(std::remove_if(points.begin(), points.end(), [](const SweepPoint& p) { return !(p.value > 0.0); }),
    points.end());
}

// A configuration's series on a cost-growth chart: the technique and every setting but `omitted` (the x axis's key).
std::string costGrowthSeries(const Configuration& configuration, const std::string& omitted)
{
  std::string series = configuration.technique;
  for (const std::string& setting : configuration.settings)
  {
    series += !omitted.empty() && setting.rfind(omitted + "=", 0) == 0 ? "" : " " + setting;
  }
  return series;
}

// cost_growth_<scene>.png, when a --sweep varies shadow_map_size: each series' frame GPU time and its largest stage's
// against the map size on log-log axes, beside a line growing as the texel count (size squared) from the smallest
// size's frame time of the first series: a slope reads off how the cost grows. One chart per image size.
std::vector<std::string> writeMapSizeGrowthCharts(const nlohmann::json& rows,
  const std::vector<Configuration>& configurations, const std::vector<SceneVariant>& variants,
  const std::vector<SettingSweep>& sweeps, const BenchSizes& sizes, const BenchEnvironment& environment,
  const std::filesystem::path& dir)
{
  const std::string key = "shadow_map_size";
  if (!sweptKeys(sweeps).count(key))
  {
    return {};
  }
  std::map<ChartGroup, std::vector<SweepPoint>> charts;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    if (rows[c]["status"] != "ok")
    {
      continue;
    }
    // A swept "auto" is placed at the size the frame chose, where its result says.
    std::optional<double> size = settingNumber(configurations[c].settings, key);
    size = size ? size : parseNumber(chosenMapSizeText(rows[c]["result"]));
    if (!size || !(*size > 0.0))
    {
      continue;
    }
    // Series: the technique with every setting but the map size (other swept keys too: each is its own line).
    const std::string series = costGrowthSeries(configurations[c], key);
    const nlohmann::json& result = rows[c]["result"];
    charts[chartGroupOf(configurations[c])].push_back({ series + " frame", *size, timingValue(result, "frame_gpu_ms") });
    std::string largest;
    double largestMs = -1.0;
    for (const auto& [stage, timing] : result["stages"].items())
    {
      if (timingValue(timing, "gpu_ms") > largestMs)
      {
        largestMs = timingValue(timing, "gpu_ms");
        largest = stage;
      }
    }
    if (largestMs > 0.0)
    {
      charts[chartGroupOf(configurations[c])].push_back({ series + " " + largest, *size, largestMs });
    }
  }
  std::vector<std::string> files;
  for (auto& [group, points] : charts)
  {
    dropNonPositive(points);
    if (points.empty())
    {
      continue;
    }
    addGrowthGuide(points, "size^2 (texels)", 2.0);
    files.push_back("cost_growth_" + chartGroupStem(variants, sizes, group) + ".png");
    writeSweepChart(points,
      benchChartTitle("cost against shadow_map_size: " + variants[group.first].name + " (" + sizes.texts[group.second] +
          ")",
        environment),
      { "shadow_map_size (texels across)", "GPU time (ms, median)", true, true, true }, dir / files.back());
  }
  return files;
}

// With several -r sizes, per scene variant: cost_growth_pixels_<scene>.png (frame GPU time) and
// cost_growth_pass_pixels_<scene>.png (the technique stage's GPU time) against the image's pixel count, log-log, one
// series per configuration (technique and settings) joined over the sizes, beside a line growing as the pixel count
// from the smallest size's time of the first series.
std::vector<std::string> writeImageSizeGrowthCharts(const nlohmann::json& rows,
  const std::vector<Configuration>& configurations, const std::vector<SceneVariant>& variants, const BenchSizes& sizes,
  const BenchEnvironment& environment, const std::filesystem::path& dir)
{
  if (!sizes.several())
  {
    return {};
  }
  std::map<std::size_t, std::vector<SweepPoint>> frameCharts;
  std::map<std::size_t, std::vector<SweepPoint>> passCharts;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    if (rows[c]["status"] != "ok")
    {
      continue;
    }
    const Configuration& configuration = configurations[c];
    const glm::ivec2 size = sizes.sizes[configuration.resolutionIndex];
    const double pixels = static_cast<double>(size.x) * static_cast<double>(size.y);
    const nlohmann::json& result = rows[c]["result"];
    const std::string series = costGrowthSeries(configuration, "");
    frameCharts[configuration.sceneIndex].push_back({ series, pixels, timingValue(result, "frame_gpu_ms") });
    if (result["stages"].contains("technique"))
    {
      passCharts[configuration.sceneIndex].push_back(
        { series, pixels, timingValue(result["stages"]["technique"], "gpu_ms") });
    }
  }
  std::vector<std::string> files;
  const std::string sizeList = joined(sizes.texts, ", ");
  const auto write = [&](std::map<std::size_t, std::vector<SweepPoint>>& charts, const std::string& prefix,
                       const std::string& what) {
    for (auto& [sceneIndex, points] : charts)
    {
      dropNonPositive(points);
      if (points.empty())
      {
        continue;
      }
      addGrowthGuide(points, "pixels", 1.0);
      files.push_back(prefix + variantStem(variants[sceneIndex], sceneIndex) + ".png");
      writeSweepChart(points,
        benchChartTitle(what + " against image size: " + variants[sceneIndex].name + " (" + sizeList + ")", environment),
        { "image size (pixels)", what + " (ms, median)", true, true, true }, dir / files.back());
    }
  };
  write(frameCharts, "cost_growth_pixels_", "frame GPU time");
  write(passCharts, "cost_growth_pass_pixels_", "technique pass GPU time");
  return files;
}

// The least-squares slope of log(value) against log(x): the exponent k of value ~ x^k. Empty with fewer than two
// distinct positive x or a value <= 0.
std::optional<double> logLogSlope(const std::vector<std::pair<double, double>>& points)
{
  double sumX = 0.0;
  double sumY = 0.0;
  for (const auto& [x, y] : points)
  {
    if (!(x > 0.0) || !(y > 0.0))
    {
      return std::nullopt;
    }
    sumX += std::log(x);
    sumY += std::log(y);
  }
  const double n = static_cast<double>(points.size());
  double sxx = 0.0;
  double sxy = 0.0;
  for (const auto& [x, y] : points)
  {
    sxx += (std::log(x) - sumX / n) * (std::log(x) - sumX / n);
    sxy += (std::log(x) - sumX / n) * (std::log(y) - sumY / n);
  }
  return points.size() >= 2 && sxx > 0.0 ? std::optional<double>(sxy / sxx) : std::nullopt;
}

// summary.md's "Cost growth against image size" (several -r sizes): per scene and configuration the frame GPU ms at
// each size and the exponents k of frame ms ~ pixels^k and technique-pass ms ~ pixels^k (least squares on log-log
// axes; 1: the cost grows as the pixels, 0: it does not depend on them, as a structure built at a fixed map size).
std::string costGrowthMarkdown(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchSizes& sizes)
{
  if (!sizes.several())
  {
    return {};
  }
  struct Growth
  {
    std::map<std::size_t, double> frameMs; // by size index
    std::vector<std::pair<double, double>> frame;
    std::vector<std::pair<double, double>> pass;
  };
  std::map<std::pair<std::size_t, std::string>, Growth> series; // (scene, technique and settings)
  std::vector<std::pair<std::size_t, std::string>> order;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    if (rows[c]["status"] != "ok")
    {
      continue;
    }
    const Configuration& configuration = configurations[c];
    const std::pair<std::size_t, std::string> key{ configuration.sceneIndex, costGrowthSeries(configuration, "") };
    if (!series.count(key))
    {
      order.push_back(key);
    }
    Growth& growth = series[key];
    const nlohmann::json& result = rows[c]["result"];
    const glm::ivec2 size = sizes.sizes[configuration.resolutionIndex];
    const double pixels = static_cast<double>(size.x) * static_cast<double>(size.y);
    growth.frameMs[configuration.resolutionIndex] = timingValue(result, "frame_gpu_ms");
    growth.frame.emplace_back(pixels, timingValue(result, "frame_gpu_ms"));
    if (result["stages"].contains("technique"))
    {
      growth.pass.emplace_back(pixels, timingValue(result["stages"]["technique"], "gpu_ms"));
    }
  }
  std::ostringstream markdown;
  markdown << "\n## Cost growth against image size\n\n"
           << "Frame GPU ms (median) at " << joined(sizes.texts, ", ")
           << "; k: the exponent of time ~ pixels^k, a least-squares fit on log-log axes (1: the time grows as the "
              "pixels; near 0: it is spent on work the image size does not change, such as a structure built at a "
              "fixed map size). Charts: cost_growth_pixels_<scene>.png, cost_growth_pass_pixels_<scene>.png; every "
              "number in cost_growth.csv.\n\n"
           << "| scene | configuration | frame ms | frame k | technique pass k |\n| --- | --- | --- | ---: | ---: |\n";
  const auto exponent = [](const std::optional<double>& k) {
    std::ostringstream text;
    if (k)
    {
      text << std::fixed << std::setprecision(2) << *k;
    }
    return k ? text.str() : std::string("-");
  };
  for (const auto& key : order)
  {
    const Growth& growth = series.at(key);
    std::string times;
    for (std::size_t r = 0; r < sizes.texts.size(); ++r)
    {
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(2);
      if (growth.frameMs.count(r))
      {
        cell << growth.frameMs.at(r);
      }
      times += (r == 0 ? "" : ", ") + (growth.frameMs.count(r) ? cell.str() : std::string("-"));
    }
    markdown << "| " << variants[key.first].name << " | " << key.second << " | " << times << " | "
             << exponent(logLogSlope(growth.frame)) << " | " << exponent(logLogSlope(growth.pass)) << " |\n";
  }
  return markdown.str();
}

// cost_growth.csv, beside any cost-growth chart: per ok configuration its size, map size (as set, and as the frame
// rendered it, chosen under shadow_map_size=auto: bench-run's shadow_map_size_chosen where the result has it), frame
// and technique-pass GPU times, and each structure's build time and bytes.
void writeCostGrowthCsv(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const BenchSizes& sizes, const std::filesystem::path& dir)
{
  const std::vector<std::string> structures = structureColumns(rows);
  std::vector<std::string> header{ "technique", "settings", "scene", "scene_overrides", "resolution", "pixels",
    "shadow_map_size", "shadow_map_size_chosen", "frame_gpu_ms", "technique_gpu_ms", "structures_build_gpu_ms" };
  for (const std::string& structure : structures)
  {
    header.insert(header.end(), { structure + "_build_gpu_ms", structure + "_gpu_bytes" });
  }
  std::ostringstream csv;
  csv << joined(header, ",") << "\n";
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    if (row["status"] != "ok")
    {
      continue;
    }
    const nlohmann::json& result = row["result"];
    const glm::ivec2 size = sizes.sizes[configurations[c].resolutionIndex];
    const auto number = [](double value) { return numberText(nlohmann::json(value)); };
    const nlohmann::json parameters = result.value("parameters", nlohmann::json::object());
    std::vector<std::string> cells{ row["technique"].get<std::string>(), csvField(row["settings"]),
      csvField(row["scene"]), csvField(row["scene_overrides"]), row["resolution"].get<std::string>(),
      format(static_cast<long long>(size.x) * size.y),
      parameterText(parameters.value("shadow_map_size", nlohmann::json())), chosenMapSizeText(result),
      number(timingValue(result, "frame_gpu_ms")),
      result["stages"].contains("technique") ? number(timingValue(result["stages"]["technique"], "gpu_ms")) : "" };
    const std::vector<StructureCost> costs = structureCostsOf(result);
    cells.push_back(number(totalBuildMs(costs)));
    for (const std::string& structure : structures)
    {
      const auto cost =
        std::find_if(costs.begin(), costs.end(), [&](const StructureCost& item) { return item.name == structure; });
      cells.push_back(cost == costs.end() ? "" : number(cost->buildMs));
      cells.push_back(cost == costs.end() ? "" : format(static_cast<unsigned long long>(cost->bytes)));
    }
    csv << joined(cells, ",") << "\n";
  }
  writeFileChecked(dir / "cost_growth.csv", csv.str());
}

// " 128x128": a row's image size for a series name when the bench runs several (its lines would join sizes
// otherwise), else "".
std::string seriesSizeTag(const nlohmann::json& row, const BenchOptions& options)
{
  return options.resolution.find(',') == std::string::npos ? std::string() : " " + row["resolution"].get<std::string>();
}

// With exactly one numeric --scene-sweep (e.g. light sizes): sweep_time_<scene>.png and sweep_rmse_<scene>.png,
// frame GPU time and RMSE against the swept value, per scene file; one series per technique and settings.
void writeSceneSweepCharts(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchOptions& options, const BenchEnvironment& environment,
  const std::filesystem::path& dir)
{
  if (options.sceneSweeps.size() != 1)
  {
    return;
  }
  std::map<std::string, std::vector<SweepPoint>> sweepTimes;
  std::map<std::string, std::vector<SweepPoint>> sweepErrors;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    const SceneVariant& variant = variants[configurations[c].sceneIndex];
    if (row["status"] != "ok" || !row["result"].contains("error") || variant.swept.size() != 1)
    {
      continue;
    }
    const nlohmann::json& result = row["result"];
    const std::string& swept = variant.swept.front();
    const std::optional<double> parameter = parseNumber(swept.substr(swept.find('=') + 1));
    const std::string series = row["technique"].get<std::string>() +
      (row["settings"].get<std::string>().empty() ? "" : " " + row["settings"].get<std::string>()) +
      seriesSizeTag(row, options);
    if (parameter)
    {
      sweepTimes[variant.file].push_back({ series, *parameter, result["frame_gpu_ms"].get<double>() });
      sweepErrors[variant.file].push_back({ series, *parameter, result["error"]["covered"]["rmse"].get<double>() });
    }
  }
  const std::string pointer = options.sceneSweeps.front().substr(0, options.sceneSweeps.front().find('='));
  for (const auto& [file, points] : sweepTimes)
  {
    const std::string stem = std::filesystem::path(file).parent_path().filename().string();
    const bool positive = std::all_of(points.begin(), points.end(), [](const SweepPoint& p) { return p.parameter > 0.0; });
    writeSweepChart(points,
      benchChartTitle("frame GPU time against " + pointer + ": " + stem + " (" + options.resolution + ")", environment),
      { pointer, "frame GPU time (ms)", positive, true }, dir / ("sweep_time_" + stem + ".png"));
    writeSweepChart(sweepErrors.at(file),
      benchChartTitle("RMSE against " + pointer + ": " + stem + " (" + options.resolution + ")", environment),
      { pointer, "RMSE of visibility vs ray-traced reference", positive, false }, dir / ("sweep_rmse_" + stem + ".png"));
  }
}

// --depth-profile: depth_profile.csv, a row per configuration and bin (with the closed form where the frame has one,
// metrics/DepthProfile.h), and depth_profile_<scene>.png, the medians and closed forms against the eye's depth plus
// logarithmic warping's closed form (§4.2.1) for the first configuration that has a closed form.
void writeDepthProfiles(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchOptions& options, const BenchEnvironment& environment,
  const std::filesystem::path& dir)
{
  if (options.depthProfile.empty())
  {
    return;
  }
  std::ostringstream csv;
  csv << "scene,scene_overrides,technique,settings,buffer,bin,near_depth,far_depth,pixels,depth_median,lower_quartile,"
         "median,upper_quartile,closed_form,median_over_closed_form,n,z_near,z_far,logarithmic_closed_form\n";
  std::map<std::size_t, std::vector<DepthProfileSeries>> charts;
  std::map<std::size_t, nlohmann::json> logarithmic;
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    if (row["status"] != "ok" || !row["result"].contains("depth_profile"))
    {
      continue;
    }
    const nlohmann::json& profile = row["result"]["depth_profile"];
    const nlohmann::json form = profile.value("closed_form", nlohmann::json());
    const auto formText = [&](const char* key) {
      return form.is_object() && form[key].is_number() ? numberText(form[key]) : std::string();
    };
    DepthProfileSeries series;
    series.name = row["technique"].get<std::string>() +
      (row["settings"].get<std::string>().empty() ? "" : " " + row["settings"].get<std::string>()) +
      seriesSizeTag(row, options);
    for (std::size_t b = 0; b < profile["bins"].size(); ++b)
    {
      const nlohmann::json& bin = profile["bins"][b];
      csv << csvField(row["scene"]) << "," << csvField(row["scene_overrides"]) << "," << row["technique"].get<std::string>()
          << "," << csvField(row["settings"]) << "," << profile["buffer"].get<std::string>() << "," << b << ","
          << numberText(bin["near_depth"]) << "," << numberText(bin["far_depth"]) << "," << bin["pixels"].get<std::size_t>();
      for (const char* key : { "depth_median", "lower_quartile", "median", "upper_quartile" })
      {
        csv << "," << (bin["pixels"].get<std::size_t>() > 0 ? numberText(bin[key]) : std::string());
      }
      for (const char* key : { "closed_form", "median_over_closed_form" })
      {
        csv << "," << (bin.contains(key) ? numberText(bin[key]) : std::string());
      }
      csv << "," << formText("n") << "," << formText("z_near") << "," << formText("z_far") << ","
          << formText("logarithmic") << "\n";
      if (bin["pixels"].get<std::size_t>() > 0)
      {
        series.depths.push_back(bin["depth_median"].get<double>());
        series.medians.push_back(bin["median"].get<double>());
      }
    }
    if (form.is_object())
    {
      // The closed form over [z_n, z_f], 200 steps; n null is the uniform limit.
      Fig12ClosedForm closed;
      closed.zNear = form["z_near"].get<double>();
      closed.zFar = form["z_far"].get<double>();
      closed.n = form["n"].is_number() ? form["n"].get<double>() : std::numeric_limits<double>::infinity();
      closed.pixelsPerUnit = form["pixels_per_unit"].get<double>();
      closed.texelsAcrossBody = form["texels_across_body"].get<double>();
      for (int i = 0; i <= 200; ++i)
      {
        const double z = closed.zNear + (closed.zFar - closed.zNear) * i / 200.0;
        series.curveDepths.push_back(z);
        series.curveValues.push_back(closed.at(z));
      }
      logarithmic.emplace(configurations[c].sceneIndex, form);
    }
    charts[configurations[c].sceneIndex].push_back(series);
  }
  writeFileChecked(dir / "depth_profile.csv", csv.str());
  for (auto& [sceneIndex, series] : charts)
  {
    if (logarithmic.count(sceneIndex))
    {
      const nlohmann::json& form = logarithmic.at(sceneIndex);
      DepthProfileSeries line;
      line.name = "logarithmic warping (closed form, §4.2.1)";
      line.curveDepths = { form["z_near"].get<double>(), form["z_far"].get<double>() };
      line.curveValues = { form["logarithmic"].get<double>(), form["logarithmic"].get<double>() };
      series.push_back(line);
    }
    const SceneVariant& variant = variants[sceneIndex];
    std::string stem = std::filesystem::path(variant.file).parent_path().filename().string();
    stem = stem.empty() ? std::to_string(sceneIndex) : stem;
    writeDepthProfileChart(series,
      benchChartTitle(options.depthProfile + " median per depth bin: " + variant.name + " (" + options.resolution + ")",
        environment),
      options.depthProfile, dir / ("depth_profile_" + stem + ".png"));
  }
}

// --view-stats with a --sweep: against the first swept key's value (e.g. cascades, swept jointly with a matching
// shadow_map_size so that every point has the same total texels), per scene variant, view_<buffer>_<scene>.png
// (each series' largest and mean value over the view) and sweep_above_0.05_<scene>.png (the share of covered pixels
// wrong by more than 0.05: for hard shadows against a one-sample reference of a point or directional light, the
// misclassified pixels). A series is a technique and its settings other than the first sweep's keys.
void writeViewStatisticCharts(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchOptions& options, const std::vector<SettingSweep>& sweeps,
  const BenchEnvironment& environment, const std::filesystem::path& dir)
{
  if (options.viewStats.empty() || sweeps.empty())
  {
    return;
  }
  const std::vector<std::string>& axisKeys = sweeps.front().keys;
  const std::string& axis = axisKeys.front();
  const std::vector<std::string> buffers = splitList(options.viewStats, "--view-stats " + options.viewStats);
  std::map<std::size_t, std::map<std::string, std::vector<SweepPoint>>> charts; // scene variant -> chart -> points
  for (std::size_t c = 0; c < rows.size(); ++c)
  {
    const nlohmann::json& row = rows[c];
    const std::optional<double> x = settingNumber(configurations[c].settings, axis);
    if (row["status"] != "ok" || !x)
    {
      continue;
    }
    std::string series = row["technique"].get<std::string>();
    for (const std::string& setting : configurations[c].settings)
    {
      const std::string key = setting.substr(0, setting.find('='));
      series += std::find(axisKeys.begin(), axisKeys.end(), key) == axisKeys.end() ? " " + setting : "";
    }
    series += seriesSizeTag(row, options);
    const nlohmann::json& result = row["result"];
    auto& sceneCharts = charts[configurations[c].sceneIndex];
    for (const std::string& buffer : buffers)
    {
      const nlohmann::json values = result.value("view_stats", nlohmann::json::object()).value(buffer, nlohmann::json::object());
      if (values.contains("max"))
      {
        sceneCharts[buffer].push_back({ series + " max", *x, values["max"].get<double>() });
        sceneCharts[buffer].push_back({ series + " mean", *x, values["mean"].get<double>() });
      }
    }
    if (result.contains("error"))
    {
      sceneCharts[""].push_back({ series, *x, result["error"]["covered"]["fraction_above_0.05"].get<double>() });
    }
  }
  for (const auto& [sceneIndex, sceneCharts] : charts)
  {
    const SceneVariant& variant = variants[sceneIndex];
    std::string stem = std::filesystem::path(variant.file).parent_path().filename().string();
    stem = stem.empty() ? std::to_string(sceneIndex) : stem;
    for (const auto& [buffer, points] : sceneCharts)
    {
      const bool positiveX = std::all_of(points.begin(), points.end(), [](const SweepPoint& p) { return p.parameter > 0.0; });
      const bool positiveY = std::all_of(points.begin(), points.end(), [](const SweepPoint& p) { return p.value > 0.0; });
      if (buffer.empty())
      {
        writeSweepChart(points,
          benchChartTitle("pixels wrong by more than 0.05 against " + axis + ": " + variant.name + " (" +
              options.resolution + ")", environment),
          { axis, "share of covered pixels wrong by more than 0.05", positiveX, positiveY },
          dir / ("sweep_above_0.05_" + stem + ".png"));
        continue;
      }
      writeSweepChart(points,
        benchChartTitle(buffer + " over the view (max, mean) against " + axis + ": " + variant.name + " (" +
            options.resolution + ")", environment),
        { axis, buffer + " over the view", positiveX, positiveY }, dir / ("view_" + buffer + "_" + stem + ".png"));
    }
  }
}

// bench.json, bench.csv, the charts and thumbnail strips, then summary.md (which lists them).
// bench.json, bench.csv, the charts and thumbnail strips, cost_growth.csv beside a cost-growth chart, then summary.md
// (which lists them); `baseline` (--baseline): the comparison with an earlier bench's rows.
void writeBenchResults(const nlohmann::json& rows, const std::vector<Configuration>& configurations,
  const std::vector<SceneVariant>& variants, const BenchOptions& options, const BenchSizes& sizes,
  const std::vector<SettingSweep>& sweeps, const std::optional<BenchBaseline>& baseline, const std::filesystem::path& dir)
{
  const BenchEnvironment environment = benchEnvironment(rows);
  const std::vector<BaselineMatch> matches = baseline ? matchBaseline(rows, *baseline) : std::vector<BaselineMatch>{};
  nlohmann::json configurationsJson = rows;
  for (std::size_t r = 0; r < configurationsJson.size(); ++r)
  {
    nlohmann::json& row = configurationsJson[r];
    if (row["status"] == "ok")
    {
      row["statistics"] = statisticsOf(row["result"]); // every counter; summary.md shows at most three
      nlohmann::json structures = nlohmann::json::object();
      for (const StructureCost& cost : structureCostsOf(row["result"]))
      {
        const auto stages = structureBuildStages().find(cost.name);
        structures[cost.name] = { { "build_gpu_ms", cost.buildMs }, { "gpu_bytes", cost.bytes },
          { "stages", stages == structureBuildStages().end() ? std::vector<std::string>{} : stages->second } };
      }
      row["structures"] = structures;
    }
    if (baseline)
    {
      const BaselineMatch& match = matches[r];
      row["baseline"] = match.problem.empty()
        ? nlohmann::json{ { "rmse", match.baseline.rmse }, { "rmse_delta", match.rmse - match.baseline.rmse },
            { "penumbra_rmse", match.baseline.penumbraRmse ? nlohmann::json(*match.baseline.penumbraRmse) : nlohmann::json() },
            { "p99_abs_error", match.baseline.p99AbsError ? nlohmann::json(*match.baseline.p99AbsError) : nlohmann::json() },
            { "settings", match.baseline.settings }, { "worse", match.worse } }
        : nlohmann::json{ { "problem", match.problem } };
    }
  }
  nlohmann::json benchJson = { { "resolution", options.resolution }, { "resolutions", sizes.texts },
    { "repeat", options.repeat }, { "reference_samples", options.referenceSamples },
    { "renderer", environment.renderer }, { "gl_version", environment.glVersion },
    { "machine", { { "cpu", environment.cpu }, { "logical_cores", environment.logicalCores } } },
    { "configurations", configurationsJson } };
  if (baseline)
  {
    benchJson["baseline"] = { { "dir", baseline->dir }, { "rule", baselineRuleText() },
      { "worse_absolute", kBaselineWorseAbsolute }, { "worse_relative", kBaselineWorseRelative } };
  }
  writeJson(benchJson, dir / "bench.json");
  const std::set<std::string> statisticNames = statisticNamesOf(rows);
  writeFileChecked(dir / "bench.csv", benchCsv(rows, statisticNames, baseline ? &matches : nullptr));
  std::vector<std::string> charts = writeStageCharts(rows, configurations, variants, sizes, environment, dir);
  for (const std::vector<std::string>& more :
    { writeSpeedErrorCharts(rows, configurations, variants, sweeps, sizes, environment, dir),
      writeThumbnailStrips(rows, configurations, variants, sizes, environment, dir),
      writeMapSizeGrowthCharts(rows, configurations, variants, sweeps, sizes, environment, dir),
      writeImageSizeGrowthCharts(rows, configurations, variants, sizes, environment, dir) })
  {
    charts.insert(charts.end(), more.begin(), more.end());
  }
  if (std::any_of(charts.begin(), charts.end(), [](const std::string& file) { return file.rfind("cost_growth", 0) == 0; }))
  {
    writeCostGrowthCsv(rows, configurations, sizes, dir);
    charts.push_back("cost_growth.csv");
  }
  writeSceneSweepCharts(rows, configurations, variants, options, environment, dir);
  writeDepthProfiles(rows, configurations, variants, options, environment, dir);
  writeViewStatisticCharts(rows, configurations, variants, options, sweeps, environment, dir);
  writeFileChecked(dir / "open_in_paraview.py", benchParaViewScript());
  writeFileChecked(dir / "summary.md",
    summaryMarkdown(rows, options, sizes, environment, charts,
      costGrowthMarkdown(rows, configurations, variants, sizes) +
        (baseline ? baselineMarkdown(rows, matches, *baseline, options.referenceSamples) : std::string())));
}

// bench --plan (cli/BenchPlan.h): every reference the configurations need and is not in the cache yet (whole, or as
// --reference-tiles row tiles and their merge), then every configuration; paths absolute, results under the plan.
std::vector<PlanJob> benchPlanJobs(const BenchOptions& options, const BenchSizes& sizes,
  const std::vector<SceneVariant>& variants, const std::vector<Configuration>& configurations, std::ostream& log)
{
  const std::filesystem::path planDir = planDirectory(options);
  for (std::size_t r = 0; r < sizes.sizes.size(); ++r)
  {
    if (options.referenceTiles > sizes.sizes[r].y)
    {
      throw InputError(format("--reference-tiles ", options.referenceTiles, ": more than the ", sizes.sizes[r].y,
        " rows of --resolution ", sizes.texts[r]));
    }
  }
  std::map<ChartGroup, std::set<int>> needed;
  for (const Configuration& configuration : configurations)
  {
    needed[chartGroupOf(configuration)].insert(multisamplesOf(configuration));
  }
  std::vector<PlanJob> jobs;
  std::set<std::string> planned;
  for (const auto& [group, samples] : needed)
  {
    const SceneVariant& variant = variants[group.first];
    const std::string& resolutionText = sizes.texts[group.second];
    for (const int msaa : samples)
    {
      const std::string key = referenceKey(variant.scene, resolutionText, options.referenceSamples, msaa);
      const std::filesystem::path cached = std::filesystem::path(options.cacheDir) / key;
      const std::string name = "reference of " + variant.name +
        (sizes.several() ? " at " + resolutionText : std::string()) +
        (msaa > 1 ? format(" (", msaa, " per pixel)") : "");
      if (cachedReferenceProblem(cached, sizes.sizes[group.second]).empty())
      {
        if (!options.quiet)
        {
          log << "bench: " << name << " is in the cache (" << cached.string() << "), no job\n";
        }
        continue;
      }
      if (!planned.insert(key).second)
      {
        continue;
      }
      std::vector<std::string> arguments{ "reference", variant.file, "--reference-samples",
        std::to_string(options.referenceSamples), "--resolution", resolutionText, "--msaa", std::to_string(msaa),
        "--quiet" };
      for (const std::string& override : variant.overrides)
      {
        arguments.insert(arguments.end(), { "--scene-set", override });
      }
      if (options.referenceTiles == 1)
      {
        std::vector<std::string> whole = arguments;
        whole.insert(whole.end(), { "--out", cached.string(), "--force" }); // the cache's entry, as bench replaces it
        jobs.push_back({ "references", name, whole, "logs/reference-" + key + ".txt", cached.string() });
        continue;
      }
      std::vector<std::string> merge{ "reference-merge" };
      for (int k = 0; k < options.referenceTiles; ++k)
      {
        const std::filesystem::path tileDir = planDir / "tiles" / key / std::to_string(k);
        std::vector<std::string> tile = arguments;
        tile.insert(tile.end(), { "--tile", format(k, "/", options.referenceTiles), "--out", tileDir.string() });
        jobs.push_back({ "references", format(name, " (tile ", k, " of ", options.referenceTiles, ")"), tile,
          format("logs/reference-", key, "-tile", k, ".txt"), tileDir.string() });
        merge.push_back(tileDir.string());
      }
      merge.insert(merge.end(), { "--out", cached.string(), "--quiet", "--force" });
      jobs.push_back({ "merges", name + " (merge of the tiles)", merge, "logs/merge-" + key + ".txt", cached.string() });
    }
  }
  for (std::size_t c = 0; c < configurations.size(); ++c)
  {
    const Configuration& configuration = configurations[c];
    const SceneVariant& variant = variants[configuration.sceneIndex];
    const std::filesystem::path result = planDir / "runs" / format(c, ".json");
    const std::string& resolutionText = sizes.texts[configuration.resolutionIndex];
    const std::filesystem::path reference = std::filesystem::path(options.cacheDir) /
      referenceKey(variant.scene, resolutionText, options.referenceSamples, multisamplesOf(configuration)) /
      "buffers.vti";
    jobs.push_back({ "configurations",
      format("configuration ", c, " (", configuration.technique, configuration.settings.empty() ? "" : " ",
        joined(configuration.settings, " "), " on ", variant.name,
        sizes.several() ? " at " + resolutionText : std::string(), ")"),
      benchRunArguments(options, sizes, variant, configuration, reference.string(), result.string() + ".partial"),
      format("logs/run-", c, ".txt"), result.string() });
  }
  return jobs;
}

// bench --collect: the rows of the plan's configurations from what their tasks wrote; every unfinished job (a
// reference, merge or configuration) named in `log` and returned in `unfinished`.
// The finished configurations' results are copied to `dir`/runs/<n>.json as a bench writes them, and their thumbnails
// (bench-run's <result>.thumbnail.vti, the result being named <n>.json.partial in a plan) to where
// writeThumbnailStrips reads a bench's.
nlohmann::json collectedRows(const LoadedPlan& plan, const std::vector<SceneVariant>& variants,
  const std::vector<Configuration>& configurations, const BenchSizes& sizes, std::vector<PlanJob>& unfinished, std::ostream& log,
  const std::filesystem::path& dir)
{
  std::vector<const PlanJob*> configurationJobs;
  for (const PlanJob& job : plan.jobs)
  {
    const std::string problem = planJobProblem(plan.dir, job);
    if (!problem.empty())
    {
      log << "bench: " << job.name << ": " << problem << "\n"; // said even with --quiet: rows are missing
      unfinished.push_back(job);
    }
    if (job.stage == "configurations")
    {
      configurationJobs.push_back(&job);
    }
  }
  if (configurationJobs.size() != configurations.size())
  {
    throw InputError(format("--collect ", plan.dir.string(), ": the plan lists ", configurationJobs.size(),
      " configurations, its options give ", configurations.size(), " (planned by another version?)"));
  }
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t c = 0; c < configurations.size(); ++c)
  {
    const PlanJob& job = *configurationJobs[c];
    rows.push_back(configurationRow(variants[configurations[c].sceneIndex], configurations[c], sizes, job.result,
      planJobProblem(plan.dir, job)));
    if (rows.back()["status"] != "ok")
    {
      continue;
    }
    // runs/<n>.json as a bench writes them.
    std::filesystem::create_directories(dir / "runs");
    std::filesystem::copy_file(job.result, dir / "runs" / format(c, ".json"));
    const std::filesystem::path thumbnail =
      std::filesystem::path(job.result + ".partial").replace_extension(".thumbnail.vti");
    if (std::filesystem::is_regular_file(thumbnail))
    {
      std::filesystem::copy_file(thumbnail, dir / "runs" / format(c, ".thumbnail.vti"));
    }
  }
  return rows;
}

} // namespace

int runBench(const BenchOptions& given, std::ostream& log)
{
  // --plan and --collect (cli/BenchPlan.h): the same bench as jobs, from the options the plan saved.
  checkPlanOptions(given);
  std::optional<LoadedPlan> plan;
  BenchOptions options = given;
  if (!given.collectDir.empty())
  {
    plan = loadBenchPlan(given.collectDir);
    options = plan->options;
    options.outDir = given.outDir;
    options.force = given.force;
    options.quiet = given.quiet;
    options.progress = given.progress;
  }
  else if (!given.planDir.empty())
  {
    for (std::string& scene : options.sceneFiles)
    {
      scene = std::filesystem::absolute(scene).lexically_normal().string(); // the tasks run anywhere
    }
    options.cacheDir = std::filesystem::absolute(options.cacheDir).lexically_normal().string();
  }
  // Everything the user typed is checked before any child runs.
  checkScenesRepeatAndSamples(options);
  checkSceneOverrides(options.sceneOverrides, options.sceneSweeps);
  const BenchSizes sizes = parseBenchSizes(options.resolution);
  if (!given.baselineDir.empty() && !given.planDir.empty())
  {
    throw InputError("--baseline " + given.baselineDir + ": give it to bench --collect, not to --plan");
  }
  // Read before any child runs: a bad DIR is one line and no output.
  const std::optional<BenchBaseline> baseline =
    given.baselineDir.empty() ? std::nullopt : std::optional(loadBenchBaseline(given.baselineDir));
  const std::vector<SceneVariant> variants = loadSceneVariants(options);
  const std::vector<std::string> techniqueNames = selectedTechniqueNames(options.techniques);
  const std::vector<SettingSweep> sweeps = parseSettingSweeps(options.sweeps);
  depthProfileSettings(options.depthProfile, options.depthBins, options.depthRange); // its errors, before any run
  if (!options.viewStats.empty())
  {
    splitList(options.viewStats, "--view-stats " + options.viewStats); // an empty item, before any run
  }
  checkSettingKeys(options.settings, sweeps, techniqueNames);
  const std::vector<Configuration> configurations =
    expandConfigurations(variants.size(), sizes.texts.size(), techniqueNames, options.settings, sweeps);
  std::vector<std::filesystem::path> inputs = benchInputs(options, variants, configurations);
  if (baseline)
  {
    inputs.push_back(given.baselineDir); // --out may neither be nor hold nor lie inside it
  }
  if (!options.planDir.empty())
  {
    writeBenchPlan(options, benchPlanJobs(options, sizes, variants, configurations, log), inputs, log);
    return 0;
  }
  if (plan)
  {
    inputs.push_back(plan->dir);
  }
  const OutputTarget output{ options.outDir, "bench", options.force, inputs };
  checkOutputTarget(output);
  if (plan)
  {
    std::vector<PlanJob> unfinished;
    int failed = 0;
    writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
      const nlohmann::json rows = collectedRows(*plan, variants, configurations, sizes, unfinished, log, dir);
      failed = countFailed(rows);
      writeBenchResults(rows, configurations, variants, options, sizes, sweeps, baseline, dir);
      if (!unfinished.empty())
      {
        writeRetryLists(plan->dir, unfinished, dir);
      }
    });
    if (!options.quiet || !unfinished.empty())
    {
      log << "shadowlab: bench of " << configurations.size() << " configuration(s) collected from "
          << printable(given.collectDir) << ", " << failed << " failed or missing -> " << printable(options.outDir)
          << (unfinished.empty() ? std::string()
                                 : format("; ", unfinished.size(), " unfinished job(s), resubmit them: ",
                                     (plan->dir / "submit.sh").string(), " ",
                                     (std::filesystem::absolute(options.outDir) / "retry").string()))
          << "\n";
    }
    return failed == 0 && unfinished.empty() ? 0 : 4;
  }
  createCacheDirectory(options.cacheDir);

  int failures = 0;
  int referenceFailures = 0;
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir / "runs");
    std::filesystem::create_directories(dir / "logs");
    const ReferenceFiles referenceFiles =
      prepareReferences(options, sizes, variants, configurations, dir / "logs", log, referenceFailures);
    const nlohmann::json rows = runConfigurations(options, sizes, variants, configurations, referenceFiles, dir, log);
    failures = countFailed(rows);
    removeIfEmptyDirectory(dir / "logs");
    writeBenchResults(rows, configurations, variants, options, sizes, sweeps, baseline, dir);
  });
  if (!options.quiet)
  {
    log << "shadowlab: bench of " << configurations.size() << " configuration(s), " << failures << " failed"
        << (referenceFailures > 0 ? format(", ", referenceFailures, " reference(s) could not be made") : std::string())
        << " -> " << printable(options.outDir) << "\n";
  }
  return failures == 0 && referenceFailures == 0 ? 0 : 4;
}

} // namespace sl
