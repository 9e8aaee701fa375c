// bench --baseline DIR (issue 33, "error no worse at the new defaults than today's"): the rows of an earlier bench's
// bench.csv, matched to this run's configurations by technique, scene file, scene overrides, resolution and the
// settings that tell a technique's configurations apart, and the rule that calls this run's error worse.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

// A configuration is worse than its baseline row when its RMSE exceeds the baseline's by more than both
// kBaselineWorseAbsolute and kBaselineWorseRelative of the baseline's RMSE: the absolute floor keeps a
// reference's own sampling noise (about 1e-5 at 1024 samples) from flagging exact techniques, the relative one
// keeps large errors from being flagged for a change in their last digit.
constexpr double kBaselineWorseAbsolute = 1e-4;
constexpr double kBaselineWorseRelative = 0.01;
bool baselineWorse(double rmse, double baselineRmse);
// The rule as summary.md states it.
std::string baselineRuleText();

// One row of the baseline's bench.csv that ran and has error metrics.
struct BaselineRow
{
  std::string scene;    // as the baseline's bench.csv names it
  std::string settings; // as typed there
  double rmse = 0.0;
  std::optional<double> penumbraRmse; // absent where the reference has no penumbra
  std::optional<double> p99AbsError;
};

struct BenchBaseline
{
  std::string dir;
  std::map<std::string, std::vector<BaselineRow>> rowsByKey; // benchBaselineKey (distinguishing settings) -> rows
  // The same rows keyed by all their settings (sortedSettings): where no row matches on the distinguishing settings
  // (this run sweeps a value the baseline set for every row), a row with the very same settings does.
  std::map<std::string, std::vector<BaselineRow>> rowsByFullKey;
  std::size_t rowCount = 0;
  int referenceSamples = 0; // of its references (its bench.json's reference_samples; 0 when it names none)
};

// The rows of DIR/bench.csv (resolution from its `resolution` column, else from DIR/bench.json's "resolution", as
// benches before the column wrote it). InputError naming `--baseline DIR` when DIR is missing, holds no
// bench.csv, or its bench.csv lacks the columns a match needs.
BenchBaseline loadBenchBaseline(const std::string& dir);

// A configuration's technique and settings (space-separated "key=value"), for distinguishingSettings.
struct BaselineSettingsOf
{
  std::string technique;
  std::string settings;
};
// Per row, its settings less those every row of its technique in the same run has (a --set value, a default the
// bench spelt out): what is left tells the technique's configurations apart (a --sweep value), sorted.
std::vector<std::string> distinguishingSettings(const std::vector<BaselineSettingsOf>& rows);

// A settings text ("b=2 a=1") with its items sorted ("a=1 b=2").
std::string sortedSettings(const std::string& settings);

// The key two benches' rows match on. `sceneFile`: its last two path components are used (the dataset folder and
// the file), so benches run from another directory or with absolute paths still match.
std::string benchBaselineKey(const std::string& technique, const std::string& sceneFile,
  const std::string& sceneOverrides, const std::string& resolution, const std::string& distinguishing);

} // namespace sl
