// bench --baseline: an earlier bench's rows and how this run's are matched to them (cli/BenchBaseline.h).
#include "cli/BenchBaseline.h"

#include "core/Error.h"
#include "core/Parse.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace sl
{
namespace
{

// The records of a CSV text as bench.csv writes it (cli/BenchCommand.cpp csvField: a cell holding ',', '"' or a
// line break is quoted, '"' doubled).
std::vector<std::vector<std::string>> baselineCsvRecords(const std::string& text)
{
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record(1);
  bool quoted = false;
  bool any = false;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    any = true;
    if (quoted)
    {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
      {
        record.back() += '"';
        ++i;
      }
      else if (c == '"')
      {
        quoted = false;
      }
      else
      {
        record.back() += c;
      }
    }
    else if (c == '"')
    {
      quoted = true;
    }
    else if (c == ',')
    {
      record.emplace_back();
    }
    else if (c == '\n')
    {
      records.push_back(record);
      record.assign(1, std::string());
      any = false;
    }
    else if (c != '\r')
    {
      record.back() += c;
    }
  }
  if (any)
  {
    records.push_back(record);
  }
  return records;
}

std::vector<std::string> baselineSplitSettings(const std::string& settings)
{
  std::vector<std::string> items;
  std::istringstream stream(settings);
  for (std::string item; stream >> item;)
  {
    items.push_back(item);
  }
  return items;
}

std::string baselineSceneTail(const std::string& sceneFile)
{
  const std::filesystem::path path = std::filesystem::path(sceneFile).lexically_normal();
  const std::string folder = path.parent_path().filename().string();
  return folder.empty() ? path.filename().string() : folder + "/" + path.filename().string();
}

} // namespace

bool baselineWorse(double rmse, double baselineRmse)
{
  const double increase = rmse - baselineRmse;
  return increase > kBaselineWorseAbsolute && increase > kBaselineWorseRelative * baselineRmse;
}

std::string baselineRuleText()
{
  std::ostringstream text;
  text << "a configuration is worse when its RMSE exceeds the baseline's by more than " << kBaselineWorseAbsolute
       << " absolute and by more than " << 100.0 * kBaselineWorseRelative << " % of the baseline's RMSE";
  return text.str();
}

std::vector<std::string> distinguishingSettings(const std::vector<BaselineSettingsOf>& rows)
{
  // Per technique, the settings every one of its rows has.
  std::map<std::string, std::set<std::string>> common;
  std::set<std::string> seen;
  for (const BaselineSettingsOf& row : rows)
  {
    const std::vector<std::string> items = baselineSplitSettings(row.settings);
    const std::set<std::string> mine(items.begin(), items.end());
    if (seen.insert(row.technique).second)
    {
      common[row.technique] = mine;
      continue;
    }
    std::set<std::string> kept;
    std::set_intersection(common[row.technique].begin(), common[row.technique].end(), mine.begin(), mine.end(),
      std::inserter(kept, kept.begin()));
    common[row.technique] = kept;
  }
  std::vector<std::string> result;
  for (const BaselineSettingsOf& row : rows)
  {
    std::vector<std::string> items = baselineSplitSettings(row.settings);
    items.erase(std::remove_if(items.begin(), items.end(),
                  [&](const std::string& item) { return common[row.technique].count(item) > 0; }),
      items.end());
    std::sort(items.begin(), items.end());
    std::string text;
    for (const std::string& item : items)
    {
      text += (text.empty() ? "" : " ") + item;
    }
    result.push_back(text);
  }
  return result;
}

std::string sortedSettings(const std::string& settings)
{
  std::vector<std::string> items = baselineSplitSettings(settings);
  std::sort(items.begin(), items.end());
  std::string text;
  for (const std::string& item : items)
  {
    text += (text.empty() ? "" : " ") + item;
  }
  return text;
}

std::string benchBaselineKey(const std::string& technique, const std::string& sceneFile,
  const std::string& sceneOverrides, const std::string& resolution, const std::string& distinguishing)
{
  return technique + "\t" + baselineSceneTail(sceneFile) + "\t" + sceneOverrides + "\t" + resolution + "\t" +
    distinguishing;
}

BenchBaseline loadBenchBaseline(const std::string& dir)
{
  const std::string named = "--baseline " + dir;
  if (!std::filesystem::is_directory(dir))
  {
    throw InputError(named + ": no such directory (give an earlier bench's --out)");
  }
  const std::filesystem::path csvFile = std::filesystem::path(dir) / "bench.csv";
  std::ifstream csv(csvFile);
  if (!std::filesystem::is_regular_file(csvFile) || !csv)
  {
    throw InputError(named + ": no bench.csv in it (not the output of a bench)");
  }
  const std::vector<std::vector<std::string>> records =
    baselineCsvRecords(std::string(std::istreambuf_iterator<char>(csv), std::istreambuf_iterator<char>()));
  if (records.empty())
  {
    throw InputError(named + ": bench.csv is empty");
  }
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < records[0].size(); ++i)
  {
    column[records[0][i]] = i;
  }
  for (const char* needed : { "scene", "scene_overrides", "technique", "settings", "status", "rmse" })
  {
    if (!column.count(needed))
    {
      throw InputError(named + ": bench.csv has no column '" + needed + "'");
    }
  }
  // Benches before the resolution column ran one size, which bench.json states; it also names the references'
  // sample count.
  nlohmann::json benchJson;
  {
    std::ifstream jsonFile(std::filesystem::path(dir) / "bench.json");
    try
    {
      benchJson = jsonFile ? nlohmann::json::parse(jsonFile) : nlohmann::json();
    }
    catch (const nlohmann::json::exception&)
    {
      benchJson = nlohmann::json();
    }
  }
  BenchBaseline baseline;
  if (benchJson.is_object() && benchJson.contains("reference_samples") && benchJson["reference_samples"].is_number())
  {
    baseline.referenceSamples = benchJson["reference_samples"].get<int>();
  }
  std::string resolution;
  if (!column.count("resolution"))
  {
    resolution = benchJson.is_object() && benchJson.contains("resolution") && benchJson["resolution"].is_string()
      ? benchJson["resolution"].get<std::string>()
      : std::string();
    if (resolution.empty() || resolution.find(',') != std::string::npos)
    {
      throw InputError(named + ": bench.csv has no resolution column and bench.json names no single resolution");
    }
  }
  baseline.dir = dir;
  std::vector<std::vector<std::string>> usable;
  std::vector<BaselineSettingsOf> settings;
  const auto cell = [&](const std::vector<std::string>& record, const std::string& name) {
    const std::size_t at = column.at(name);
    return at < record.size() ? record[at] : std::string();
  };
  for (std::size_t r = 1; r < records.size(); ++r)
  {
    settings.push_back({ cell(records[r], "technique"), cell(records[r], "settings") });
  }
  // Which settings tell configurations apart is a property of the whole run, failed rows included.
  const std::vector<std::string> distinguishing = distinguishingSettings(settings);
  const auto optionalNumber = [&](const std::vector<std::string>& record, const char* name) -> std::optional<double> {
    return column.count(name) ? parseNumber(cell(record, name)) : std::nullopt;
  };
  for (std::size_t r = 1; r < records.size(); ++r)
  {
    const std::vector<std::string>& record = records[r];
    const std::optional<double> rmse = parseNumber(cell(record, "rmse"));
    if (cell(record, "status") != "ok" || !rmse)
    {
      continue;
    }
    BaselineRow row;
    row.scene = cell(record, "scene");
    row.settings = cell(record, "settings");
    row.rmse = *rmse;
    row.penumbraRmse = optionalNumber(record, "penumbra_rmse");
    row.p99AbsError = optionalNumber(record, "p99_abs_error");
    const std::string rowResolution = column.count("resolution") ? cell(record, "resolution") : resolution;
    const std::string key = benchBaselineKey(cell(record, "technique"), row.scene, cell(record, "scene_overrides"),
      rowResolution, distinguishing[r - 1]);
    baseline.rowsByKey[key].push_back(row);
    baseline.rowsByFullKey[benchBaselineKey(cell(record, "technique"), row.scene, cell(record, "scene_overrides"),
                             rowResolution, sortedSettings(row.settings))]
      .push_back(row);
    ++baseline.rowCount;
  }
  return baseline;
}

} // namespace sl
