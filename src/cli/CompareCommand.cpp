// shadowlab compare: error metrics of a technique's buffers against a reference (src/metrics).
#include "cli/Commands.h"

#include "core/Error.h"
#include "io/OutputDirectory.h"
#include "metrics/Comparison.h"

#include <iomanip>

namespace sl
{

int runCompare(const CompareOptions& options, std::ostream& log)
{
  const OutputTarget output{ options.outDir, "compare", options.force, { options.testFile, options.referenceFile } };
  checkOutputTarget(output);
  const Comparison comparison = compareVtiFiles(options.testFile, options.referenceFile, options.array);
  writeComparison(comparison, options.testFile, options.referenceFile, output);
  if (!options.quiet)
  {
    const ErrorStatistics& covered = comparison.metrics.covered;
    const ErrorStatistics& penumbra = comparison.metrics.penumbra;
    log << std::setprecision(4) << "shadowlab: " << printable(options.array) << " of " << printable(options.testFile)
        << " vs " << printable(options.referenceFile) << ": RMSE " << covered.rmse << ", MAE " << covered.mae << ", max "
        << covered.maxAbsError << ", >0.05 " << covered.fractionAbove005 << " over " << covered.pixels
        << " px; penumbra RMSE " << penumbra.rmse << " over " << penumbra.pixels << " px -> " << printable(options.outDir) << "\n";
  }
  return 0;
}

} // namespace sl
