// bench --plan / --collect: the bench as jobs (cli/BenchPlan.h).
#include "cli/BenchPlan.h"

#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "output/OutputWriter.h"

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace sl
{
namespace
{

constexpr const char* kPlanFormat = "shadowlab-bench-plan";

// One word of a POSIX shell, whatever bytes it holds.
std::string shellWord(const std::string& word)
{
  std::string quoted = "'";
  for (const char c : word)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

// The job's command line: this executable with its arguments, output to its log; a configuration's result is
// written beside its name and renamed when complete, so a result file is never half of one.
std::string jobLine(const std::filesystem::path& planDir, const std::string& executable, const PlanJob& job)
{
  std::string line = shellWord(executable);
  for (const std::string& argument : job.arguments)
  {
    line += " " + shellWord(argument);
  }
  line += " > " + shellWord((planDir / job.log).string()) + " 2>&1";
  if (job.stage == "configurations")
  {
    line += " && mv -f " + shellWord(job.result + ".partial") + " " + shellWord(job.result);
  }
  return line;
}

std::string stageList(const std::filesystem::path& planDir, const std::string& executable,
  const std::vector<PlanJob>& jobs, const std::string& stage)
{
  std::string text;
  for (const PlanJob& job : jobs)
  {
    if (stage.empty() || job.stage == stage)
    {
      text += jobLine(planDir, executable, job) + "\n";
    }
  }
  return text;
}

// One array task: line SLURM_ARRAY_TASK_ID + 1 of the list given as the script's argument.
std::string taskScript(const BenchOptions& options, const std::filesystem::path& planDir)
{
  std::ostringstream script;
  script << "#!/bin/bash\n"
         << "# One task of a ShadowLab bench plan: line SLURM_ARRAY_TASK_ID + 1 of the job list given as $1\n"
         << "# (submit.sh submits each stage of the plan as an array of these).\n"
         << "#SBATCH --job-name=shadowlab-bench\n"
         << "#SBATCH --output=" << (planDir / "logs" / "slurm-%A_%a.txt").string() << "\n";
  if (!options.slurmPartition.empty())
  {
    script << "#SBATCH --partition=" << options.slurmPartition << "\n";
  }
  if (!options.slurmTime.empty())
  {
    script << "#SBATCH --time=" << options.slurmTime << "\n";
  }
  if (options.slurmGpus > 0)
  {
    script << "#SBATCH --gres=gpu:" << options.slurmGpus << "\n";
  }
  script << "set -u\n"
         << "list=\"$1\"\n"
         << "line=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$list\")\n"
         << "if [ -z \"$line\" ]; then echo \"no task $SLURM_ARRAY_TASK_ID in $list\" >&2; exit 2; fi\n"
         << "exec bash -c \"$line\"\n";
  return script.str();
}

// Submits every non-empty stage list of a directory (the plan's, or a collect's retry/) as a job array that starts
// after the previous stage's array has ended (afterany: a configuration whose reference failed still runs and
// says so in its row).
std::string submitScript(const BenchOptions& options, const std::filesystem::path& planDir)
{
  std::ostringstream script;
  script << "#!/bin/bash\n"
         << "# Submits the ShadowLab bench plan in " << planDir.string() << " to Slurm: each stage a job array,\n"
         << "# after the stage before it. Argument: a directory of <stage>.txt lists (default: the plan's; a\n"
         << "# `bench --collect` writes OUT/retry with only the unfinished jobs). Prints the job ids.\n"
         << "set -euo pipefail\n"
         << "plan=" << shellWord(planDir.string()) << "\n"
         << "lists=$(cd \"${1:-$plan}\" && pwd)\n"
         << "throttle=" << options.slurmThrottle << "\n"
         << "dependency=\n"
         << "for stage in";
  for (const std::string& stage : benchPlanStages())
  {
    script << " " << stage;
  }
  script << "; do\n"
         << "  tasks=$(grep -c . \"$lists/$stage.txt\" || true)\n"
         << "  [ \"$tasks\" -gt 0 ] || continue\n"
         << "  array=\"0-$((tasks - 1))\"\n"
         << "  [ \"$throttle\" -eq 0 ] || array=\"$array%$throttle\"\n"
         << "  id=$(sbatch --parsable ${dependency:+--dependency=afterany:$dependency} --array=\"$array\" \\\n"
         << "    \"$plan/task.sbatch\" \"$lists/$stage.txt\")\n"
         << "  dependency=${id%%;*}\n"
         << "  echo \"$stage: job array $dependency ($tasks tasks)\"\n"
         << "done\n";
  return script.str();
}

nlohmann::json optionsJson(const BenchOptions& options)
{
  return { { "scenes", options.sceneFiles }, { "techniques", options.techniques }, { "sweeps", options.sweeps },
    { "settings", options.settings }, { "scene_overrides", options.sceneOverrides },
    { "scene_sweeps", options.sceneSweeps }, { "repeat", options.repeat }, { "resolution", options.resolution },
    { "reference_samples", options.referenceSamples }, { "cache", options.cacheDir },
    { "depth_profile", options.depthProfile }, { "depth_bins", options.depthBins },
    { "depth_range", options.depthRange }, { "view_stats", options.viewStats },
    { "slurm_partition", options.slurmPartition }, { "slurm_time", options.slurmTime },
    { "slurm_gpus", options.slurmGpus }, { "slurm_throttle", options.slurmThrottle },
    { "reference_tiles", options.referenceTiles } };
}

BenchOptions optionsFromJson(const nlohmann::json& json)
{
  BenchOptions options;
  options.sceneFiles = json.at("scenes").get<std::vector<std::string>>();
  options.techniques = json.at("techniques").get<std::string>();
  options.sweeps = json.at("sweeps").get<std::vector<std::string>>();
  options.settings = json.at("settings").get<std::vector<std::string>>();
  options.sceneOverrides = json.at("scene_overrides").get<std::vector<std::string>>();
  options.sceneSweeps = json.at("scene_sweeps").get<std::vector<std::string>>();
  options.repeat = json.at("repeat").get<int>();
  options.resolution = json.at("resolution").get<std::string>();
  options.referenceSamples = json.at("reference_samples").get<int>();
  options.cacheDir = json.at("cache").get<std::string>();
  options.depthProfile = json.at("depth_profile").get<std::string>();
  options.depthBins = json.at("depth_bins").get<int>();
  options.depthRange = json.at("depth_range").get<std::string>();
  options.viewStats = json.at("view_stats").get<std::string>();
  options.referenceTiles = json.at("reference_tiles").get<int>();
  return options;
}

} // namespace

void checkPlanOptions(const BenchOptions& options)
{
  if (!options.planDir.empty() && !options.collectDir.empty())
  {
    throw InputError("--plan and --collect: give one (plan a bench, then collect what its tasks wrote)");
  }
  if (!options.collectDir.empty() && !options.sceneFiles.empty())
  {
    throw InputError("--collect " + options.collectDir + ": give no scene (the plan names the scenes and options)");
  }
  const bool slurmGiven = !options.slurmPartition.empty() || !options.slurmTime.empty() || options.slurmGpus != 0 ||
    options.slurmThrottle != 0 || options.referenceTiles != 1;
  if (options.planDir.empty() && slurmGiven)
  {
    throw InputError("--slurm-partition, --slurm-time, --slurm-gpus, --slurm-throttle and --reference-tiles: only "
                     "with --plan DIR");
  }
  // Slurm's own spellings (sbatch(1)): a partition name without spaces or shell characters, and the time formats
  // "minutes", "minutes:seconds", "hours:minutes:seconds", "days-hours", "days-hours:minutes",
  // "days-hours:minutes:seconds".
  if (!options.slurmPartition.empty() && !std::regex_match(options.slurmPartition, std::regex("[A-Za-z0-9_.-]+")))
  {
    throw InputError("--slurm-partition " + options.slurmPartition + ": expected a partition name (letters, digits, "
      "'_', '.', '-')");
  }
  if (!options.slurmTime.empty() &&
    !std::regex_match(options.slurmTime, std::regex("[0-9]+(:[0-9]+){0,2}|[0-9]+-[0-9]+(:[0-9]+){0,2}")))
  {
    throw InputError("--slurm-time " + options.slurmTime + ": expected MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM or "
      "D-HH:MM:SS");
  }
  if (options.slurmGpus < 0)
  {
    throw InputError(format("--slurm-gpus ", options.slurmGpus, ": must be >= 0"));
  }
  if (options.slurmThrottle < 0)
  {
    throw InputError(format("--slurm-throttle ", options.slurmThrottle, ": must be >= 0 (0: no limit)"));
  }
  if (options.referenceTiles < 1)
  {
    throw InputError(format("--reference-tiles ", options.referenceTiles, ": must be >= 1"));
  }
}

std::filesystem::path planDirectory(const BenchOptions& options)
{
  return std::filesystem::absolute(options.planDir).lexically_normal();
}

void writeBenchPlan(const BenchOptions& options, const std::vector<PlanJob>& jobs,
  const std::vector<std::filesystem::path>& inputs, std::ostream& log)
{
  const std::filesystem::path planDir = planDirectory(options);
  const std::string executable = std::filesystem::read_symlink("/proc/self/exe").string();
  const OutputTarget output{ options.planDir, "bench-plan", options.force, inputs };
  try
  {
    checkOutputTarget(output);
  }
  catch (const InputError& error)
  {
    // The contract's message names --out; the user typed --plan.
    const std::string message = error.what();
    throw InputError(message.rfind("--out ", 0) == 0 ? "--plan " + message.substr(6) : message);
  }
  nlohmann::json jobList = nlohmann::json::array();
  for (const PlanJob& job : jobs)
  {
    jobList.push_back({ { "stage", job.stage }, { "name", job.name }, { "arguments", job.arguments },
      { "log", job.log }, { "result", job.result }, { "line", jobLine(planDir, executable, job) } });
  }
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    for (const char* sub : { "logs", "runs", "tiles" })
    {
      std::filesystem::create_directories(dir / sub);
    }
    writeJson({ { "format", kPlanFormat }, { "version", 1 }, { "executable", executable },
                { "options", optionsJson(options) }, { "jobs", jobList } },
      dir / "plan.json");
    writeFileChecked(dir / "jobs.txt", stageList(planDir, executable, jobs, ""));
    for (const std::string& stage : benchPlanStages())
    {
      writeFileChecked(dir / (stage + ".txt"), stageList(planDir, executable, jobs, stage));
    }
    writeFileChecked(dir / "task.sbatch", taskScript(options, planDir));
    writeFileChecked(dir / "submit.sh", submitScript(options, planDir));
    std::filesystem::permissions(dir / "submit.sh",
      std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec,
      std::filesystem::perm_options::add);
  });
  if (!options.quiet)
  {
    std::map<std::string, int> counts;
    for (const PlanJob& job : jobs)
    {
      ++counts[job.stage];
    }
    log << "shadowlab: bench plan of " << counts["references"] << " reference job(s), " << counts["merges"]
        << " merge(s), " << counts["configurations"] << " configuration(s) -> " << printable(options.planDir)
        << " (run: bash " << printable((planDir / "jobs.txt").string()) << ", or on Slurm: "
        << printable((planDir / "submit.sh").string()) << "; then bench --collect)\n";
  }
}

LoadedPlan loadBenchPlan(const std::string& planDirText)
{
  const std::filesystem::path file = std::filesystem::path(planDirText) / "plan.json";
  std::ifstream stream(file);
  nlohmann::json plan;
  try
  {
    plan = stream ? nlohmann::json::parse(stream) : nlohmann::json();
  }
  catch (const nlohmann::json::exception&)
  {
    plan = nlohmann::json();
  }
  if (!plan.is_object() || plan.value("format", "") != kPlanFormat)
  {
    throw InputError("--collect " + planDirText + ": not a bench plan (no plan.json written by bench --plan)");
  }
  LoadedPlan loaded;
  try
  {
    loaded.options = optionsFromJson(plan.at("options"));
    for (const nlohmann::json& job : plan.at("jobs"))
    {
      loaded.jobs.push_back({ job.at("stage").get<std::string>(), job.at("name").get<std::string>(),
        job.at("arguments").get<std::vector<std::string>>(), job.at("log").get<std::string>(),
        job.at("result").get<std::string>() });
    }
  }
  catch (const nlohmann::json::exception&)
  {
    throw InputError("--collect " + planDirText + ": plan.json is damaged (a field is missing or of another type)");
  }
  loaded.dir = std::filesystem::absolute(planDirText).lexically_normal();
  return loaded;
}

std::string planJobProblem(const std::filesystem::path& planDir, const PlanJob& job)
{
  const std::filesystem::path result(job.result);
  const bool done = job.stage == "configurations"
    ? std::filesystem::is_regular_file(result)
    : std::filesystem::is_regular_file(result / "buffers.vti") &&
      std::filesystem::is_regular_file(result / "stats.json");
  if (done)
  {
    return {};
  }
  std::ifstream log(planDir / job.log);
  if (!log)
  {
    return "missing (never started: no " + job.log + ")";
  }
  std::string last;
  for (std::string line; std::getline(log, line);)
  {
    last = line.empty() ? last : line;
  }
  return last.empty() ? "failed or still running (" + job.log + " is empty)" : "failed: " + last;
}

void writeRetryLists(const std::filesystem::path& planDir, const std::vector<PlanJob>& unfinished,
  const std::filesystem::path& dir)
{
  std::ifstream stream(planDir / "plan.json");
  const std::string executable = nlohmann::json::parse(stream).value("executable", "shadowlab");
  std::filesystem::create_directories(dir / "retry");
  for (const std::string& stage : benchPlanStages())
  {
    writeFileChecked(dir / "retry" / (stage + ".txt"), stageList(planDir, executable, unfinished, stage));
  }
}

} // namespace sl
