// Every argument of every command that names a file or directory, with what the command does there: the one list
// the output contract (io/OutputDirectory.h, docs/outputs.md) is checked against, argument by
// argument (tests/cli/PathOptionsTest.cpp), and every other argument, so that the test can tell from `--help` that
// nothing is missing. An argument added to main.cpp is one line here. Header-only: the tests read it too.
#pragma once

namespace sl
{

enum class PathRole
{
  // Replaced atomically as a whole (writeDirectoryAtomically): never an input, never holding or inside an input
  // directory, never the root, `.` or the home directory and their ancestors; an existing directory only when
  // empty or carrying the marker, or with --force.
  WritesDirectory,
  // One file replaced atomically (TemporaryOutputFile): never an input nor inside an input directory; an existing
  // file only when the command wrote it (montage: a PNG with its "Software: ShadowLab montage" text; view --record:
  // a recording), or with --force.
  WritesFile,
  // New files under a directory, numbered or named by a hash, never replacing a user's file (view's screenshots,
  // bench's cache entries; `--out` may not lie inside the cache).
  AddsFiles,
  // Read only: an input of the command, which no output of it may be, hold or lie inside. `--set`, `--sweep` and
  // `--scene-set` read the files their values name (a technique's file parameter, a scene's mesh or texture).
  Reads,
  // bench-run's result file: hidden, named by bench inside its own temporary output directory.
  Internal,
};

struct PathArgument
{
  const char* command;
  const char* name; // the long option, or the positional's name as --help shows it
  PathRole role;
};

inline constexpr PathArgument kPathArguments[] = {
  { "render", "scene", PathRole::Reads },
  { "render", "--set", PathRole::Reads },
  { "render", "--scene-set", PathRole::Reads },
  { "render", "--out", PathRole::WritesDirectory },
  { "reference", "scene", PathRole::Reads },
  { "reference", "--scene-set", PathRole::Reads },
  { "reference", "--out", PathRole::WritesDirectory },
  { "compare", "test", PathRole::Reads },
  { "compare", "reference", PathRole::Reads },
  { "compare", "--out", PathRole::WritesDirectory },
  { "bench", "scenes", PathRole::Reads },
  { "bench", "--set", PathRole::Reads },
  { "bench", "--sweep", PathRole::Reads },
  { "bench", "--scene-set", PathRole::Reads },
  { "bench", "--scene-sweep", PathRole::Reads },
  { "bench", "--cache", PathRole::AddsFiles },
  { "bench", "--out", PathRole::WritesDirectory },
  { "bench", "--plan", PathRole::WritesDirectory },
  { "bench", "--collect", PathRole::Reads },
  { "bench", "--baseline", PathRole::Reads },
  { "reference-merge", "tiles", PathRole::Reads },
  { "reference-merge", "--out", PathRole::WritesDirectory },
  { "bench-run", "scene", PathRole::Reads },
  { "bench-run", "--set", PathRole::Reads },
  { "bench-run", "--scene-set", PathRole::Reads },
  { "bench-run", "--reference", PathRole::Reads },
  { "bench-run", "--result", PathRole::Internal },
  { "probe", "scene", PathRole::Reads },
  { "probe", "--set", PathRole::Reads },
  { "probe", "--scene-set", PathRole::Reads },
  { "probe", "--out", PathRole::WritesDirectory },
  { "view", "scene", PathRole::Reads },
  { "view", "--set", PathRole::Reads },
  { "view", "--scene-set", PathRole::Reads },
  { "view", "--play", PathRole::Reads },
  { "view", "--record", PathRole::WritesFile },
  { "view", "--screenshot-dir", PathRole::AddsFiles },
  { "montage", "runs", PathRole::Reads },
  { "montage", "--reference", PathRole::Reads },
  { "montage", "--out", PathRole::WritesFile },
  { "lessons", "--out", PathRole::WritesDirectory }, // reads the source tree's datasets/
  { "differential", "--out", PathRole::WritesDirectory }, // its scenes are generated, it reads no file
};

// The arguments that take a value naming no file or directory (flags take none and are not listed).
struct OtherArguments
{
  const char* command;
  const char* names; // space-separated
};

inline constexpr OtherArguments kOtherArguments[] = {
  { "render", "--technique --resolution --light" },
  { "reference", "--reference-samples --sampling --light-samples --seed --msaa --resolution --light --threads --tile" },
  { "reference-merge", "" },
  { "compare", "--array" },
  { "bench", "--technique --repeat --resolution --reference-samples --depth-profile --depth-bins --depth-range --view-stats "
             "--slurm-partition --slurm-time --slurm-gpus --slurm-throttle --reference-tiles" },
  { "bench-run", "--technique --resolution --repeat --depth-profile --depth-bins --depth-range --view-stats" },
  { "probe", "--technique --pixel --pick --resolution --light" },
  { "view", "--technique --resolution --light" },
  { "montage", "--buffer" },
  { "lessons", "--resolution --only" },
  { "list", "techniques" },
  { "differential", "--seeds --technique --choice --max-side --reference-samples" },
};

} // namespace sl
