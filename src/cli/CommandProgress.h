// Where the long commands' progress lines go (bench per configuration, lessons per lesson, reference per batch of
// rows), and how often: the one rule, shared by every command, over core/Progress.h's reporter (elapsed time and
// the time left from done/total). docs/tools.md, "Progress".
#pragma once

#include "core/Progress.h"

#include <ostream>

namespace sl
{

// The --progress and --quiet switches of a command.
struct ProgressSwitches
{
  bool forced = false; // --progress: progress lines even when stderr is not a terminal, and even with --quiet
  bool quiet = false;  // --quiet: none, unless --progress
};

// `log` when --progress was given, or when stderr is a terminal and --quiet was not; else nullptr, and the
// Progress prints nothing (logs and tests read one line per result, not a stream of estimates).
std::ostream* commandProgressStream(const ProgressSwitches& switches, std::ostream& log);

// With --progress, a line after every unit from the first (whoever asked sees each step); on a terminal, lines only
// when the run is expected to take at least a few seconds, then one every few seconds.
ProgressSettings commandProgressSettings(const ProgressSwitches& switches);

} // namespace sl
