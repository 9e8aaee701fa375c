#include "cli/CommandProgress.h"

#include <unistd.h>

namespace sl
{

std::ostream* commandProgressStream(const ProgressSwitches& switches, std::ostream& log)
{
  if (switches.forced)
  {
    return &log;
  }
  return !switches.quiet && ::isatty(STDERR_FILENO) ? &log : nullptr;
}

ProgressSettings commandProgressSettings(const ProgressSwitches& switches)
{
  ProgressSettings settings;
  // "Longer than a few seconds" (issue 31): a run expected to end sooner than this says nothing on a terminal.
  settings.announceAfterSeconds = switches.forced ? 0.0 : 3.0;
  settings.intervalSeconds = switches.forced ? 0.0 : 5.0;
  settings.alwaysReportTotal = switches.forced; // a run done at its first report still says how long it took
  return settings;
}

} // namespace sl
