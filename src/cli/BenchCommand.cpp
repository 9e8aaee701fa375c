// shadowlab bench: speed against error for scenes x techniques x parameter sweeps.
//
// Every configuration runs in its own process (`shadowlab bench-run`), so a sweep can be spread over
// machines by any batch system and a crash in one configuration is reported while the rest go on. The
// ray-traced reference of each scene is computed once (`shadowlab reference`, also a child process) and
// cached under --cache, keyed by a hash of the loaded scene (geometry, lights, camera), the resolution and
// the sample count. Outputs (atomically, into --out): bench.csv, bench.json, summary.md, one
// speed_vs_error_<scene>.png per scene, runs/<n>.json (each child's result), logs/ (each child's stderr).
// Exit status: 0 when every configuration ran, 4 when some failed (their rows say why).
#include "cli/Commands.h"

#include "core/Error.h"
#include "core/Parse.h"
#include "io/ImageIO.h"
#include "output/OutputWriter.h"
#include "metrics/Comparison.h"
#include "scene/Scene.h"
#include "techniques/Registry.h"
#include "vis/SpeedErrorChart.h"
#include "vis/SweepChart.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <set>
#include <sstream>
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
};

std::vector<std::string> splitList(const std::string& text, char separator)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, separator))
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
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

std::string referenceKey(const Scene& scene, const std::string& resolution, int samples)
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
  return hasher.hex();
}

struct ChildResult
{
  int exitCode = -1;
  std::string lastLine; // of its stderr
};

// Runs this executable with `arguments`, stdout and stderr into `logFile`.
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
    result.lastLine = "cannot start a child process";
    return result;
  }
  int status = 0;
  setForegroundChild(pid); // SIGINT/SIGTERM to bench end the child too (OutputDirectory.h)
  waitpid(pid, &status, 0);
  setForegroundChild(0);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  std::ifstream log(logFile);
  for (std::string line; std::getline(log, line);)
  {
    if (!line.empty())
    {
      result.lastLine = line;
    }
  }
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

} // namespace

int runBench(const BenchOptions& options, std::ostream& log)
{
  // Everything the user typed is checked before any child runs.
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
    throw InputError("--samples " + std::to_string(options.referenceSamples) + ": must be >= 1");
  }
  const glm::ivec2 resolution = parseResolution(options.resolution);
  // Scene variants: every file under every combination of the scene sweeps (plus the fixed overrides).
  struct SceneVariant
  {
    std::string file;
    std::vector<std::string> overrides;
    std::vector<std::string> swept; // the sweep's part, for names
    Scene scene;
    std::string name;
  };
  std::vector<std::vector<std::string>> sceneCombinations{ {} };
  for (const std::string& sweep : options.sceneSweeps)
  {
    const std::size_t equals = sweep.find('=');
    if (sweep.empty() || sweep[0] != '/' || equals == std::string::npos || equals + 1 == sweep.size())
    {
      throw InputError("--scene-sweep '" + sweep + "': expected /json/pointer=v1,v2,...");
    }
    std::vector<std::vector<std::string>> extended;
    for (const auto& combination : sceneCombinations)
    {
      for (const std::string& value : splitList(sweep.substr(equals + 1), ','))
      {
        auto next = combination;
        next.push_back(sweep.substr(0, equals) + "=" + value);
        extended.push_back(next);
      }
    }
    sceneCombinations = extended;
  }
  std::vector<SceneVariant> variants;
  for (const std::string& file : options.sceneFiles)
  {
    for (const auto& combination : sceneCombinations)
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
  const std::vector<std::string> techniqueNames = splitList(options.techniques, ',');
  if (techniqueNames.empty())
  {
    throw InputError("--techniques '" + options.techniques + "': no technique named");
  }
  struct Sweep
  {
    std::string key;
    std::vector<std::string> values;
  };
  std::vector<Sweep> sweeps;
  for (const std::string& sweep : options.sweeps)
  {
    const std::size_t equals = sweep.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == sweep.size())
    {
      throw InputError("--sweep '" + sweep + "': expected key=v1,v2,...");
    }
    sweeps.push_back({ sweep.substr(0, equals), splitList(sweep.substr(equals + 1), ',') });
  }
  // Each key must belong to at least one selected technique and be given once: a misspelt key would
  // otherwise be dropped silently and the bench would run the defaults.
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
  for (const std::string& setting : options.settings)
  {
    checkKey("--set", setting, setting.substr(0, setting.find('=')));
  }
  for (const Sweep& sweep : sweeps)
  {
    if (sweep.values.empty())
    {
      throw InputError("--sweep " + sweep.key + ": no values");
    }
    checkKey("--sweep", sweep.key, sweep.key);
  }

  std::vector<Configuration> configurations;
  for (std::size_t sceneIndex = 0; sceneIndex < variants.size(); ++sceneIndex)
  {
    for (const std::string& name : techniqueNames)
    {
      const TechniqueDescriptor& technique = findTechnique(name);
      // Fixed settings and sweeps apply to the techniques that declare the key.
      std::vector<std::string> base;
      for (const std::string& setting : options.settings)
      {
        const std::string key = setting.substr(0, setting.find('='));
        if (technique.findParameter(key))
        {
          base.push_back(setting);
        }
      }
      std::vector<std::vector<std::string>> combinations{ base };
      for (const Sweep& sweep : sweeps)
      {
        if (!technique.findParameter(sweep.key))
        {
          continue;
        }
        std::vector<std::vector<std::string>> extended;
        for (const auto& combination : combinations)
        {
          for (const std::string& value : sweep.values)
          {
            auto next = combination;
            next.push_back(sweep.key + "=" + value);
            extended.push_back(next);
          }
        }
        combinations = extended;
      }
      for (const auto& settings : combinations)
      {
        ParameterValues check(technique);
        for (const std::string& setting : settings)
        {
          check.set(setting);
        }
        configurations.push_back({ sceneIndex, name, settings });
      }
    }
  }

  // The scenes' files and the reference cache are inputs: --out may neither hold nor replace them.
  std::vector<std::filesystem::path> inputs{ options.cacheDir };
  for (const SceneVariant& variant : variants)
  {
    const std::vector<std::filesystem::path> sceneFiles = sceneInputs(variant.scene, variant.file);
    inputs.insert(inputs.end(), sceneFiles.begin(), sceneFiles.end());
  }
  const OutputTarget output{ options.outDir, "bench", options.force, inputs };
  checkOutputTarget(output);
  std::error_code cacheError;
  std::filesystem::create_directories(options.cacheDir, cacheError);
  if (cacheError || !std::filesystem::is_directory(options.cacheDir))
  {
    throw InputError(format("--cache ", options.cacheDir, ": cannot create the directory (",
      cacheError ? cacheError.message() : "not a directory", ")"));
  }

  int failures = 0;
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir / "runs");
    std::filesystem::create_directories(dir / "logs");

    // References first, once per scene.
    std::vector<std::string> referenceFiles(variants.size());
    for (std::size_t s = 0; s < variants.size(); ++s)
    {
      const std::filesystem::path cached = std::filesystem::path(options.cacheDir) /
        referenceKey(variants[s].scene, options.resolution, options.referenceSamples);
      // A cache entry is re-validated on every use; a bad one (cut short, altered) is computed again.
      if (const std::string problem = cachedReferenceProblem(cached, resolution); !problem.empty())
      {
        if (!options.quiet)
        {
          log << "bench: ray-traced reference of " << variants[s].name << " (" << options.referenceSamples
              << " samples) -> " << cached.string()
              << (problem == "missing" ? std::string() : " (the cached one is unusable: " + problem + ")") << "\n";
        }
        // --force: the entry (named by its hash) belongs to the cache; a bad one is replaced, marker or not.
        std::vector<std::string> arguments{ "reference", variants[s].file, "--samples",
          std::to_string(options.referenceSamples), "--resolution", options.resolution, "--out", cached.string(),
          "--quiet", "--force" };
        for (const std::string& override : variants[s].overrides)
        {
          arguments.insert(arguments.end(), { "--scene-set", override });
        }
        const ChildResult child = runChild(arguments, dir / "logs" / format("reference-", s, ".txt"));
        const std::string stillWrong = child.exitCode == 0 ? cachedReferenceProblem(cached, resolution) : "";
        if (child.exitCode != 0 || !stillWrong.empty())
        {
          log << "bench: warning: no reference for " << variants[s].name << ": "
              << (child.exitCode != 0 ? child.lastLine : stillWrong) << "\n";
          continue;
        }
      }
      referenceFiles[s] = (cached / "buffers.vti").string();
    }

    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t c = 0; c < configurations.size(); ++c)
    {
      const Configuration& configuration = configurations[c];
      const std::filesystem::path resultFile = dir / "runs" / format(c, ".json");
      const SceneVariant& variant = variants[configuration.sceneIndex];
      std::vector<std::string> arguments{ "bench-run", variant.file, "--technique",
        configuration.technique, "--resolution", options.resolution, "--repeat", std::to_string(options.repeat),
        "--result", resultFile.string() };
      if (!referenceFiles[configuration.sceneIndex].empty())
      {
        arguments.insert(arguments.end(), { "--reference", referenceFiles[configuration.sceneIndex] });
      }
      for (const std::string& setting : configuration.settings)
      {
        arguments.insert(arguments.end(), { "--set", setting });
      }
      for (const std::string& override : variant.overrides)
      {
        arguments.insert(arguments.end(), { "--scene-set", override });
      }
      const ChildResult child = runChild(arguments, dir / "logs" / format("run-", c, ".txt"));
      nlohmann::json row = { { "scene", variant.file }, { "scene_overrides", joined(variant.overrides, " ") },
        { "scene_name", variant.name },
        { "technique", configuration.technique }, { "settings", joined(configuration.settings, " ") } };
      if (child.exitCode == 0 && std::filesystem::is_regular_file(resultFile))
      {
        std::ifstream file(resultFile);
        row["status"] = "ok";
        row["result"] = nlohmann::json::parse(file);
      }
      else
      {
        ++failures;
        row["status"] = "failed";
        row["error"] = child.lastLine.empty() ? format("exit status ", child.exitCode) : child.lastLine;
      }
      if (!options.quiet)
      {
        log << "bench: [" << (c + 1) << "/" << configurations.size() << "] " << configuration.technique << " "
            << joined(configuration.settings, " ") << " on " << variant.name << ": "
            << (row["status"] == "ok" ? "ok" : "FAILED: " + row["error"].get<std::string>()) << "\n";
      }
      rows.push_back(row);
    }

    // bench.json, bench.csv, summary.md, one chart per scene.
    writeJson({ { "resolution", options.resolution }, { "repeat", options.repeat },
                { "reference_samples", options.referenceSamples }, { "configurations", rows } },
      dir / "bench.json");
    const std::vector<std::string> stages{ "gbuffer", "focus", "shadow_map", "moment_map", "summed_area_table",
      "hierarchical_shadow_map", "technique", "sublight_accumulate", "shading" };
    // Whole-frame statistics some techniques report (vtkSLTechniquePass::CollectStatistics), one column each.
    std::set<std::string> statisticNames;
    for (const nlohmann::json& row : rows)
    {
      if (row["status"] == "ok" && row["result"].contains("technique_statistics"))
      {
        for (const auto& [name, value] : row["result"]["technique_statistics"].items())
        {
          statisticNames.insert(name);
        }
      }
    }
    std::ostringstream csv;
    csv << "scene,scene_overrides,technique,settings,status,frame_gpu_ms,frame_wall_ms";
    for (const std::string& stage : stages)
    {
      csv << "," << stage << "_gpu_ms";
    }
    for (const std::string& name : statisticNames)
    {
      csv << "," << name;
    }
    csv << ",rmse,mae,max_abs_error,fraction_above_0.05,penumbra_rmse,penumbra_pixels,error\n";
    std::ostringstream markdown;
    markdown << "| scene | technique | settings | GPU ms | technique GPU ms | wall ms | RMSE | penumbra RMSE | max error | statistics |\n"
             << "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
    std::map<std::size_t, std::vector<ChartPoint>> chartPoints;
    // One numeric scene sweep (e.g. light sizes): time and RMSE against the swept value, per scene file.
    std::map<std::string, std::vector<SweepPoint>> sweepTimes;
    std::map<std::string, std::vector<SweepPoint>> sweepErrors;
    for (std::size_t c = 0; c < rows.size(); ++c)
    {
      const nlohmann::json& row = rows[c];
      csv << csvField(row["scene"]) << "," << csvField(row["scene_overrides"]) << "," << row["technique"].get<std::string>() << "," << csvField(row["settings"])
          << "," << row["status"].get<std::string>();
      const auto number = [](const nlohmann::json& value) {
        std::ostringstream text;
        text << std::setprecision(6) << value.get<double>();
        return text.str();
      };
      if (row["status"] == "ok")
      {
        const nlohmann::json& result = row["result"];
        csv << "," << number(result["frame_gpu_ms"]) << "," << number(result["frame_wall_ms"]);
        for (const std::string& stage : stages)
        {
          csv << "," << (result["stages"].contains(stage) ? number(result["stages"][stage]["gpu_ms"]) : "");
        }
        std::string statistics;
        for (const std::string& name : statisticNames)
        {
          const bool has = result.contains("technique_statistics") && result["technique_statistics"].contains(name);
          csv << "," << (has ? number(result["technique_statistics"][name]) : "");
          statistics += has ? (statistics.empty() ? "" : ", ") + name + " " + number(result["technique_statistics"][name]) : "";
        }
        const bool hasError = result.contains("error");
        if (hasError)
        {
          const nlohmann::json& covered = result["error"]["covered"];
          const nlohmann::json& penumbra = result["error"]["penumbra"];
          csv << "," << number(covered["rmse"]) << "," << number(covered["mae"]) << "," << number(covered["max_abs_error"])
              << "," << number(covered["fraction_above_0.05"]) << "," << number(penumbra["rmse"]) << ","
              << penumbra["pixels"].get<std::size_t>() << ",\n";
          // One series per technique: a sweep's configurations are points of the same series.
          chartPoints[configurations[c].sceneIndex].push_back(
            { row["technique"].get<std::string>(), result["frame_gpu_ms"].get<double>(), covered["rmse"].get<double>() });
          const SceneVariant& variant = variants[configurations[c].sceneIndex];
          if (options.sceneSweeps.size() == 1 && variant.swept.size() == 1)
          {
            const std::string& swept = variant.swept.front();
            const std::optional<double> parameter = parseNumber(swept.substr(swept.find('=') + 1));
            const std::string series = row["technique"].get<std::string>() +
              (row["settings"].get<std::string>().empty() ? "" : " " + row["settings"].get<std::string>());
            if (parameter)
            {
              sweepTimes[variant.file].push_back({ series, *parameter, result["frame_gpu_ms"].get<double>() });
              sweepErrors[variant.file].push_back({ series, *parameter, covered["rmse"].get<double>() });
            }
          }
        }
        else
        {
          csv << ",,,,,,,no reference\n";
        }
        markdown << std::fixed << std::setprecision(2) << "| " << row["scene_name"].get<std::string>() << " | "
                 << row["technique"].get<std::string>() << " | " << row["settings"].get<std::string>() << " | "
                 << result["frame_gpu_ms"].get<double>() << " | "
                 << (result["stages"].contains("technique") ? result["stages"]["technique"]["gpu_ms"].get<double>() : 0.0)
                 << " | " << result["frame_wall_ms"].get<double>() << " | "
                 << std::setprecision(4)
                 << (hasError ? number(result["error"]["covered"]["rmse"]) : std::string("-")) << " | "
                 << (hasError ? number(result["error"]["penumbra"]["rmse"]) : std::string("-")) << " | "
                 << (hasError ? number(result["error"]["covered"]["max_abs_error"]) : std::string("-")) << " | "
                 << statistics << " |\n";
      }
      else
      {
        // Empty frame times, stages, statistics and the six error columns, then the error.
        csv << std::string(2 + stages.size() + statisticNames.size() + 6, ',') << "," << csvField(row["error"]) << "\n";
        markdown << "| " << row["scene_name"].get<std::string>() << " | " << row["technique"].get<std::string>() << " | "
                 << row["settings"].get<std::string>() << " | failed: " << row["error"].get<std::string>()
                 << " | | | | | | |\n";
      }
    }
    writeFileChecked(dir / "bench.csv", csv.str());
    writeFileChecked(dir / "summary.md", markdown.str());
    for (const auto& [sceneIndex, points] : chartPoints)
    {
      const SceneVariant& variant = variants[sceneIndex];
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
      writeSpeedErrorChart(points, "speed vs error: " + variant.name + " (" + options.resolution + ")",
        dir / ("speed_vs_error_" + stem + ".png"));
    }
    for (const auto& [file, points] : sweepTimes)
    {
      const std::string stem = std::filesystem::path(file).parent_path().filename().string();
      const std::string pointer = options.sceneSweeps.front().substr(0, options.sceneSweeps.front().find('='));
      const bool positive = std::all_of(points.begin(), points.end(), [](const SweepPoint& p) { return p.parameter > 0.0; });
      writeSweepChart(points, "frame GPU time against " + pointer + ": " + stem + " (" + options.resolution + ")",
        { pointer, "frame GPU time (ms)", positive, true }, dir / ("sweep_time_" + stem + ".png"));
      writeSweepChart(sweepErrors.at(file), "RMSE against " + pointer + ": " + stem + " (" + options.resolution + ")",
        { pointer, "RMSE of visibility vs ray-traced reference", positive, false }, dir / ("sweep_rmse_" + stem + ".png"));
    }
  });
  if (!options.quiet)
  {
    log << "shadowlab: bench of " << configurations.size() << " configuration(s), " << failures << " failed -> "
        << printable(options.outDir) << "\n";
  }
  return failures == 0 ? 0 : 4;
}

} // namespace sl
