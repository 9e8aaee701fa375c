// shadowlab montage RUN_DIR... --buffer NAME [--out FILE.png] [--reference DIR]: one buffer of several runs (render
// or reference output directories) side by side on one colour scale (vis/Montage.h), each panel labelled from its
// run's stats.json. Runs of different resolutions are allowed: each panel is drawn 1:1 at its own size,
// bottom-aligned, and its label then gives its resolution.
//
// The PNG is written to a temporary sibling of --out (".<name>.shadowlab-partial-<pid>") and renamed onto --out only
// when complete, so a failure leaves no partial file and an existing --out as it was. An existing --out is replaced
// only when montage wrote it (its tEXt chunk "Software" reads "ShadowLab montage"), or with --force; a PNG of the
// user's is a file montage did not create. Never an input, nor inside a RUN_DIR, even with --force.
#include "cli/Commands.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "io/OutputDirectory.h"
#include "lessons/RunMontage.h"
#include "metrics/Comparison.h"
#include "metrics/ErrorMetrics.h"
#include "vis/BufferHeatMap.h"
#include "vis/Montage.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

struct Run
{
  fs::path dir;
  std::string name; // the directory's name, as the panel shows it
  nlohmann::json stats;
  std::vector<NamedImage> buffers;
};

std::string quoted(const fs::path& path)
{
  return printable(path.string());
}

nlohmann::json readStats(const fs::path& file)
{
  std::ifstream stream(file, std::ios::binary);
  if (!stream)
  {
    throw InputError(quoted(file) + ": cannot read (" + std::strerror(errno) + ")");
  }
  try
  {
    nlohmann::json stats = nlohmann::json::parse(stream);
    if (!stats.is_object())
    {
      throw InputError(quoted(file) + ": not a stats.json document (expected a JSON object)");
    }
    return stats;
  }
  catch (const nlohmann::json::exception& error)
  {
    throw InputError(quoted(file) + ": not valid JSON (" + error.what() + ")");
  }
}

Run readRun(const std::string& argument)
{
  Run run;
  run.dir = argument;
  std::error_code error;
  if (!fs::is_directory(run.dir, error))
  {
    throw InputError("RUN_DIR " + quoted(run.dir) +
      (fs::exists(run.dir, error) ? ": not a directory" : ": no such directory"));
  }
  run.name = fs::absolute(run.dir).lexically_normal().filename().string();
  if (run.name.empty())
  {
    run.name = fs::absolute(run.dir).lexically_normal().parent_path().filename().string();
  }
  for (const char* file : { "stats.json", "buffers.vti" })
  {
    if (!fs::is_regular_file(run.dir / file, error))
    {
      throw InputError("RUN_DIR " + quoted(run.dir) + ": no " + file +
        " (montage reads the output directories of `shadowlab render` and `shadowlab reference`)");
    }
  }
  run.stats = readStats(run.dir / "stats.json");
  run.buffers = readVti(run.dir / "buffers.vti");
  return run;
}

std::string bufferNames(const std::vector<NamedImage>& buffers)
{
  std::string names;
  for (const NamedImage& named : buffers)
  {
    names += (names.empty() ? "" : ", ") + named.name;
  }
  return names;
}

const char* kindName(BufferKind kind)
{
  switch (kind)
  {
    case BufferKind::Signed: return "signed";
    case BufferKind::Categorical: return "categorical";
    case BufferKind::Continuous: return "continuous";
    case BufferKind::BitMask: return "bit-count";
    case BufferKind::SummedArea: return "summed-area";
  }
  return "?";
}

// The tEXt chunk that marks a PNG as montage's own (see checkOutFile); a standard PNG keyword, so image viewers
// show it too.
constexpr const char* kSignatureKeyword = "Software";
constexpr const char* kSignatureValue = "ShadowLab montage";

// --out: a file name ending in .png whose directory exists; an existing file there must be a montage (or --force).
void checkOutFile(const fs::path& out, bool force)
{
  std::error_code error;
  const std::string name = "--out " + quoted(out);
  if (fs::is_directory(out, error))
  {
    throw InputError(name + ": is a directory (give the PNG file to write, e.g. " + quoted(out / "montage.png") + ")");
  }
  std::string extension = out.extension().string();
  for (char& c : extension)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (extension != ".png")
  {
    throw InputError(name + ": the montage is a PNG; give a file name ending in .png");
  }
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, error))
  {
    throw InputError(name + ": directory " + quoted(parent) + " does not exist");
  }
  if (::access(parent.c_str(), W_OK | X_OK) != 0)
  {
    throw InputError(name + ": cannot write in " + quoted(parent) + " (" + std::strerror(errno) + ")");
  }
  const fs::file_status status = fs::symlink_status(out, error);
  if (fs::exists(status))
  {
    if (!fs::is_regular_file(status))
    {
      throw InputError(name + ": exists and is not a regular file; not replaced");
    }
    if (!force && readPngText(out, kSignatureKeyword).rfind(kSignatureValue, 0) != 0)
    {
      throw InputError(name + ": refused, the file exists and montage did not write it (no \"" + kSignatureKeyword +
        ": " + kSignatureValue + "\" text in it); choose another --out, or add --force to replace it");
    }
  }
}

// Writes `canvas` to a temporary sibling of `out` (io/OutputDirectory.h: removed on failure and on Ctrl-C, and by
// the next run when a killed one left it), then renames it onto `out`.
void writePngAtomically(const ImageU8& canvas, const fs::path& out)
{
  TemporaryOutputFile temporary(out);
  try
  {
    writePng(temporary.path(), canvas, { { kSignatureKeyword, kSignatureValue } });
    temporary.commit();
  }
  catch (const InputError& error)
  {
    std::string message = error.what();
    const std::string temporaryName = temporary.path().string();
    for (std::size_t at = message.find(temporaryName); at != std::string::npos; at = message.find(temporaryName))
    {
      message.replace(at, temporaryName.size(), out.string());
    }
    throw InputError("--out " + message);
  }
}

} // namespace

int runMontage(const MontageCommandOptions& options, std::ostream& log)
{
  if (options.runDirs.empty())
  {
    throw InputError("montage: give at least one RUN_DIR");
  }
  const fs::path out = options.outFile;
  checkOutFile(out, options.force);

  std::vector<Run> runs;
  for (const std::string& dir : options.runDirs)
  {
    runs.push_back(readRun(dir));
  }
  std::optional<Run> reference;
  if (!options.referenceDir.empty())
  {
    reference = readRun(options.referenceDir);
  }
  // The runs are ShadowLab's outputs: the montage goes beside them, never into one.
  std::vector<fs::path> inputs(options.runDirs.begin(), options.runDirs.end());
  if (!options.referenceDir.empty())
  {
    inputs.emplace_back(options.referenceDir);
  }
  if (const std::string reason = inputConflict(out, inputs); !reason.empty())
  {
    throw InputError("--out " + quoted(out) + ": refused, it " + printable(reason) + " (nothing was written)");
  }

  // The buffer in every run, scalar, drawn the same way in every run.
  std::vector<MontagePanel> panels;
  std::optional<BufferSpec> firstSpec;
  std::string firstRun;
  for (Run& run : runs)
  {
    const NamedImage* buffer = findNamed(run.buffers, options.buffer);
    if (!buffer)
    {
      throw InputError("RUN_DIR " + quoted(run.dir) + ": no buffer '" + printable(options.buffer) +
        "' in buffers.vti (it has: " + bufferNames(run.buffers) + ")");
    }
    const BufferSpec spec = runBufferSpec(run.stats, options.buffer);
    if (spec.kind == BufferKind::SummedArea)
    {
      throw InputError("--buffer " + printable(options.buffer) + ": is a summed-area table, whose texels are sums "
        "over rectangles (only box differences mean something); a montage shows per-pixel values");
    }
    if (buffer->image.components != 1 && spec.kind != BufferKind::BitMask)
    {
      throw InputError(format("--buffer ", printable(options.buffer), ": has ", buffer->image.components,
        " components in ", quoted(run.dir / "buffers.vti"), "; a montage shows 1-component buffers"));
    }
    if (!firstSpec)
    {
      firstSpec = spec;
      firstRun = run.dir.string();
    }
    else if (spec.kind != firstSpec->kind || spec.categoryLabels != firstSpec->categoryLabels)
    {
      throw InputError("--buffer " + printable(options.buffer) + ": is " + kindName(spec.kind) + " in " + quoted(run.dir) +
        " but " + kindName(firstSpec->kind) + (spec.kind == firstSpec->kind ? " with other categories" : "") + " in " +
        printable(firstRun) + "; one colour scale cannot show both");
    }
    MontagePanel panel;
    // A bit mask is shown as its count of set bits (vis/BufferHeatMap.h); the mask marks where it applies.
    NamedImage declared = *buffer;
    declared.kind = spec.kind;
    panel.values = heatMapValues(declared);
    panel.validMask = runValueMask(run.buffers, *buffer, spec);
    if (reference && !run.stats.contains("error"))
    {
      // The visibility error against --reference, over the pixels covered in both (as `compare`).
      const fs::path testFile = run.dir / "buffers.vti";
      const fs::path referenceFile = reference->dir / "buffers.vti";
      const ComparisonInputNames names{ printable(testFile.string()), printable(referenceFile.string()), "visibility" };
      const ImageF& testVisibility = requireArray(run.buffers, "visibility", testFile);
      const ImageF& referenceVisibility = requireArray(reference->buffers, "visibility", referenceFile);
      const NamedImage* testCoverage = findNamed(run.buffers, "coverage");
      const NamedImage* referenceCoverage = findNamed(reference->buffers, "coverage");
      const ImageF allCovered(testVisibility.width, testVisibility.height, 1, 1.0f);
      const ImageF allReferenceCovered(referenceVisibility.width, referenceVisibility.height, 1, 1.0f);
      run.stats["error"] = metricsJson(computeErrorMetrics(testVisibility, referenceVisibility,
        testCoverage ? testCoverage->image : allCovered, referenceCoverage ? referenceCoverage->image : allReferenceCovered,
        names));
    }
    panels.push_back(std::move(panel));
  }

  std::vector<std::string> names;
  std::vector<nlohmann::json> stats;
  for (const Run& run : runs)
  {
    names.push_back(run.name);
    stats.push_back(run.stats);
  }
  const std::vector<std::vector<std::string>> labels = montageRunLabels(names, stats);
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    panels[p].labels = labels[p];
  }
  MontageOptions montage;
  montage.title = options.buffer;
  montage.unit = firstSpec->unit;
  montage.kind = firstSpec->kind;
  montage.categoryLabels = firstSpec->categoryLabels;
  montage.commonLines = montageCommonLabels(stats);
  const MontageLayout layout = montageLayout(panels, montage);
  writePngAtomically(renderMontage(panels, montage), out);
  if (!options.quiet)
  {
    log << "shadowlab: montage of " << printable(options.buffer) << " from " << runs.size() << " run(s), "
        << kindName(montage.kind) << " scale [" << std::setprecision(9) << layout.colorRange.min << ", "
        << layout.colorRange.max << "], " << layout.width << "x" << layout.height << " px -> " << quoted(out) << "\n";
  }
  return 0;
}

} // namespace sl
