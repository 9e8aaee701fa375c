// A bench as data (issue 32): `bench --plan DIR` writes every job of the bench (the ray-traced references, their
// row tiles and merges, then one `bench-run` per configuration) as one shell command line each, and a Slurm batch
// script that runs each stage as a job array after the one before it; `bench --collect DIR` merges what the tasks
// wrote into the bench's usual outputs, naming the tasks that are missing or failed and listing them for a resubmit.
// The jobs share nothing but files: each writes its own output atomically (the reference cache's entries through
// io/OutputDirectory.h, a configuration's result by a rename), so tasks on many nodes of a shared filesystem may
// run in any order and side by side within a stage.
#pragma once

#include "cli/Commands.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace sl
{

// The stages, in the order they must run: every job of a stage may run beside the others of it.
inline const std::vector<std::string>& benchPlanStages()
{
  static const std::vector<std::string> stages{ "references", "merges", "configurations" };
  return stages;
}

struct PlanJob
{
  std::string stage;                  // one of benchPlanStages()
  std::string name;                   // for messages: "reference of <scene> (tile 2 of 4)", "configuration 3 ..."
  std::vector<std::string> arguments; // of this executable
  std::string log;                    // stdout and stderr, relative to the plan directory
  std::string result;                 // configurations: the result file, relative (written as <result>.partial,
                                      // renamed when complete); references: the cache entry it makes, absolute
};

// Refuses (one line, naming the option) --slurm-* values Slurm would not take, --slurm-*/--reference-tiles without
// --plan, and --plan with --collect.
void checkPlanOptions(const BenchOptions& options);

// The plan directory, absolute (the jobs run anywhere on the shared filesystem).
std::filesystem::path planDirectory(const BenchOptions& options);

// Writes plan.json, jobs.txt (every job, stage by stage: `bash jobs.txt` runs the bench), <stage>.txt, task.sbatch
// and submit.sh into options.planDir, atomically (OutputDirectory.h).
void writeBenchPlan(const BenchOptions& options, const std::vector<PlanJob>& jobs,
  const std::vector<std::filesystem::path>& inputs, std::ostream& log);

// The bench options and jobs of the plan in `planDir` (InputError naming --collect when it is not one).
struct LoadedPlan
{
  BenchOptions options;
  std::vector<PlanJob> jobs;
  std::filesystem::path dir; // absolute
};
LoadedPlan loadBenchPlan(const std::string& planDir);

// Why `job` of the plan in `planDir` has not finished ("" when its output is there): "missing (never started)"
// without a log, else the log's last line.
std::string planJobProblem(const std::filesystem::path& planDir, const PlanJob& job);

// retry/<stage>.txt (the jobs listed in `unfinished`, stage by stage) under `dir`, for `submit.sh DIR/retry`.
void writeRetryLists(const std::filesystem::path& planDir, const std::vector<PlanJob>& unfinished,
  const std::filesystem::path& dir);

} // namespace sl
