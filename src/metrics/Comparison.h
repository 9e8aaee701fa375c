// `shadowlab compare TEST.vti REF.vti [--out DIR]`: the error metrics (ErrorMetrics.h) of one array of two
// .vti files written by `shadowlab render` / the reference, and the files that show where the error is.
#pragma once

#include "io/OutputDirectory.h"
#include "metrics/ErrorMetrics.h"

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct NamedImage;

// The image `name` among the arrays read from `file`; throws InputError naming the file, the array and the
// arrays there.
const ImageF& requireArray(const std::vector<NamedImage>& arrays, const std::string& name,
  const std::filesystem::path& file);

// Reads both files (readVti), takes `array` and "coverage" from each (coverage missing in one file: the other's
// is used; missing in both: every pixel is compared) and compares them (compareImages). Throws InputError
// naming the file: missing/unreadable file, no such array (listing the arrays there), sizes differ
// ("b.vti: 64x64, but a.vti is 128x96"), NaN/inf (naming the array and the first pixel (x, y)).
Comparison compareVtiFiles(const std::filesystem::path& testFile, const std::filesystem::path& referenceFile,
  const std::string& array = "visibility");

// Writes into output.dir atomically (writeDirectoryAtomically: a failure leaves no partial output):
//  - error.vti: arrays error (test - reference, 0 where not compared), abs_error, reference, test, compared (0/1);
//  - error.png: diverging heat map of the signed error over the compared pixels, range symmetric about 0,
//    with colour key and the title "error (test - reference)";
//  - metrics.json: metricsJson plus "test", "reference" (the paths as given) and "resolution" [width, height].
// Throws InputError when output.dir is refused or cannot be written.
void writeComparison(const Comparison& comparison, const std::filesystem::path& testFile,
  const std::filesystem::path& referenceFile, const OutputTarget& output);

// The metrics.json document of writeComparison.
nlohmann::json comparisonJson(const Comparison& comparison, const std::filesystem::path& testFile,
  const std::filesystem::path& referenceFile);

} // namespace sl
