// shadowlab reference-merge: row tiles of one reference into one (cli/ReferenceTiles.h).
#include "cli/ReferenceTiles.h"

#include "cli/Commands.h"
#include "core/Error.h"
#include "core/Parse.h"
#include "io/ImageIO.h"
#include "io/OutputDirectory.h"
#include "output/OutputWriter.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <map>

namespace sl
{

RowTile parseRowTile(const std::string& text, int height)
{
  const std::size_t slash = text.find('/');
  const std::optional<double> index = slash == std::string::npos ? std::nullopt : parseNumber(text.substr(0, slash));
  const std::optional<double> count = slash == std::string::npos ? std::nullopt : parseNumber(text.substr(slash + 1));
  if (!index || !count || *index != static_cast<int>(*index) || *count != static_cast<int>(*count) || *index < 0 ||
    *count < 1 || *index >= *count)
  {
    throw InputError("--tile " + text + ": expected K/N, integers with 0 <= K < N");
  }
  if (*count > height)
  {
    throw InputError(format("--tile ", text, ": ", static_cast<int>(*count), " tiles of an image ", height,
      " rows high (at most one tile per row)"));
  }
  RowTile tile;
  tile.index = static_cast<int>(*index);
  tile.count = static_cast<int>(*count);
  // Band K starts at floor(K * H / N): the bands cover every row once, whatever N.
  tile.rowBegin = static_cast<int>(static_cast<long long>(tile.index) * height / tile.count);
  tile.rowEnd = static_cast<int>(static_cast<long long>(tile.index + 1) * height / tile.count);
  return tile;
}

namespace
{

nlohmann::json readTileStats(const std::filesystem::path& dir)
{
  std::ifstream file(dir / "stats.json");
  if (!file)
  {
    throw InputError("reference-merge " + dir.string() + ": no stats.json (not the output of reference --tile)");
  }
  nlohmann::json stats;
  try
  {
    stats = nlohmann::json::parse(file);
  }
  catch (const nlohmann::json::exception&)
  {
    throw InputError("reference-merge " + dir.string() + ": stats.json is not JSON");
  }
  if (stats.value("command", "") != "reference" || !stats.contains("tile"))
  {
    throw InputError("reference-merge " + dir.string() + ": not the output of reference --tile K/N");
  }
  return stats;
}

// What must be equal in every tile of one reference: everything but the tile, the timings and the buffers' summaries.
nlohmann::json tileIdentity(nlohmann::json stats)
{
  for (const char* key :
    { "tile", "rays_traced", "seconds", "rays_per_second", "buffers", "threads", "gl_renderer", "egl_device" })
  {
    stats.erase(key);
  }
  return stats;
}

// The arrays the tracer fills row by row; the others (the G-buffer) are whole in every tile.
bool tracedArray(const std::string& name)
{
  return name == "visibility" || name == "visibility_stderr" || name == "sample_crossings" ||
    name == "light_sample_mask";
}

} // namespace

int runReferenceMerge(const ReferenceMergeOptions& options, std::ostream& log)
{
  if (options.tileDirs.empty())
  {
    throw InputError("reference-merge: no tile directory given");
  }
  std::vector<std::filesystem::path> inputs(options.tileDirs.begin(), options.tileDirs.end());
  const OutputTarget output{ options.outDir, "reference", options.force, inputs };
  checkOutputTarget(output);

  std::map<int, std::filesystem::path> tileDirs;
  nlohmann::json identity;
  nlohmann::json merged;
  int count = 0;
  std::uint64_t rays = 0;
  double seconds = 0.0;
  for (const std::string& dirText : options.tileDirs)
  {
    const std::filesystem::path dir(dirText);
    const nlohmann::json stats = readTileStats(dir);
    const nlohmann::json& tile = stats["tile"];
    const int index = tile["index"].get<int>();
    if (tileDirs.empty())
    {
      identity = tileIdentity(stats);
      merged = stats;
      count = tile["count"].get<int>();
    }
    else if (tileIdentity(stats) != identity || tile["count"].get<int>() != count)
    {
      throw InputError("reference-merge " + dirText + ": a tile of another reference (scene, samples, seed, "
        "resolution or tile count differ from " + tileDirs.begin()->second.string() + ")");
    }
    if (!tileDirs.emplace(index, dir).second)
    {
      throw InputError(format("reference-merge ", dirText, ": tile ", index, " given twice (also ",
        tileDirs.at(index).string(), ")"));
    }
    rays += stats.value("rays_traced", std::uint64_t{ 0 });
    seconds += stats.value("seconds", 0.0);
  }
  if (static_cast<int>(tileDirs.size()) != count)
  {
    std::string missing;
    for (int k = 0; k < count; ++k)
    {
      missing += tileDirs.count(k) ? "" : (missing.empty() ? "" : ", ") + std::to_string(k);
    }
    throw InputError(format("reference-merge: tile(s) ", missing, " of ", count, " missing"));
  }

  std::vector<NamedImage> buffers;
  for (const auto& [index, dir] : tileDirs)
  {
    const std::vector<NamedImage> tileBuffers = readVti(dir / "buffers.vti");
    const nlohmann::json tile = readTileStats(dir)["tile"];
    const int rowBegin = tile["row_begin"].get<int>();
    const int rowEnd = tile["row_end"].get<int>();
    if (buffers.empty())
    {
      buffers = tileBuffers;
    }
    if (tileBuffers.size() != buffers.size())
    {
      throw InputError("reference-merge " + dir.string() + ": buffers.vti holds other arrays than tile 0's");
    }
    for (std::size_t b = 0; b < buffers.size(); ++b)
    {
      ImageF& target = buffers[b].image;
      const ImageF& source = tileBuffers[b].image;
      if (tileBuffers[b].name != buffers[b].name || source.width != target.width || source.height != target.height ||
        source.components != target.components || rowBegin < 0 || rowEnd > target.height || rowBegin > rowEnd)
      {
        throw InputError("reference-merge " + dir.string() + ": buffers.vti does not match tile 0's (" +
          tileBuffers[b].name + ")");
      }
      if (!tracedArray(buffers[b].name))
      {
        continue;
      }
      const std::size_t rowValues = static_cast<std::size_t>(target.width) * target.components;
      std::copy(source.data.begin() + rowBegin * rowValues, source.data.begin() + rowEnd * rowValues,
        target.data.begin() + rowBegin * rowValues);
    }
  }
  merged.erase("tile");
  merged["merged_tiles"] = count;
  merged["rays_traced"] = rays;
  merged["seconds"] = seconds; // the tiles' own, summed (they may have run side by side)
  merged["rays_per_second"] = seconds > 0.0 ? static_cast<double>(rays) / seconds : 0.0;
  merged["buffers"] = bufferSummaries(buffers);
  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    writeBufferFiles(buffers, {}, nullptr, dir);
    writeJson(merged, dir / "stats.json");
  });
  if (!options.quiet)
  {
    log << "shadowlab: reference of " << count << " tiles merged -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
