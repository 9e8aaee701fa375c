// The output contract: every directory of results ShadowLab writes (render, reference, compare, bench, and
// every command added later) goes through writeDirectoryAtomically, which never destroys what ShadowLab did
// not create. docs/outputs.md ("Outputs and exit codes") states the same rules for users:
//
//  - Each output directory carries a marker file, `.shadowlab-output` (JSON: tool, command, version, time, pid and
//    host; a temporary sibling is judged stale only on the host that made it, for shared filesystems).
//  - --out may replace an existing directory only when it is empty or carries that marker. A non-empty
//    directory without it is refused with one line, unless the command was given --force.
//  - Even with --force, these are always refused: the filesystem root, the current directory and each of its
//    ancestors, the home directory ($HOME and the password database's) and its ancestors, and any directory
//    holding an input of the command (scene, mesh, alpha texture, a technique's file parameter, compared file,
//    bench cache). Paths are compared after resolving symbolic links.
//  - Results go into a temporary sibling `.shadowlab-partial-<pid>-<n>` (with the marker) that takes the place
//    of --out in one atomic exchange (renameat2 RENAME_EXCHANGE) only when every file was written; a failure at
//    any point leaves the previous --out as it was. SIGINT, SIGTERM and SIGHUP remove the run's temporary
//    directory before the process ends with the signal; a temporary sibling whose process is gone (SIGKILL,
//    power loss) is removed by the next run that writes next to it.
#pragma once

#include "core/Error.h"

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

// Where a command writes, and what it must not destroy.
struct OutputTarget
{
  std::filesystem::path dir;                 // --out as the user gave it
  std::string command;                       // "render", "reference", "compare", "bench", ...
  bool force = false;                        // --force: replace a non-empty directory without the marker
  std::vector<std::filesystem::path> inputs; // files and directories the command reads (never deleted)
};

// The marker file's name inside every output directory.
inline constexpr const char* kOutputMarkerName = ".shadowlab-output";

// Throws InputError (one line naming --out and the reason) when `target` may not be written. Commands call it
// before any expensive work, so a refusal comes at once; writeDirectoryAtomically checks again before replacing.
void checkOutputTarget(const OutputTarget& target);

// Runs `writeFiles(temporaryDir)`, then puts temporaryDir in the place of target.dir atomically. Throws what
// writeFiles throws, or InputError when the target is refused or the results cannot be moved into place; the
// temporary directory is removed then and target.dir is left as it was.
template <typename WriteFiles>
void writeDirectoryAtomically(const OutputTarget& target, WriteFiles writeFiles);

// Writes `bytes` (text or binary) to `path`, checking every step (open, each write, close): InputError naming
// the file and the system's reason (e.g. "File too large", "No space left on device") on failure.
void writeFileChecked(const std::filesystem::path& path, const std::string& bytes);

// Why `output` (a directory or a file some command writes) may not be written, given that command's `inputs`:
// it is or holds an input, or lies inside an input directory (paths resolved); empty when none.
std::string inputConflict(const std::filesystem::path& output, const std::vector<std::filesystem::path>& inputs);

// The user's home directories --out may never be nor hold: $HOME, and the password database's home of the
// real user (a shell expands ~ from it when HOME is unset), resolved; each once.
std::vector<std::filesystem::path> protectedHomeDirectories();

// Installs the SIGINT/SIGTERM/SIGHUP handlers that remove the temporary directory being written (if any) and
// forward the signal to a running child process (bench); then the process ends with the signal. SIGXFSZ is
// ignored, so a write past the file size limit is a failed write (EFBIG). main() calls this once.
void installOutputSignalHandlers();
// The child process a signal is forwarded to (0: none). Set by bench around each child it waits for.
void setForegroundChild(int pid);

// The single-file variant (montage's PNG): a temporary sibling `.<name>.shadowlab-partial-<pid>` of `file`,
// renamed onto it by commit() only when complete; removed otherwise, by SIGINT/SIGTERM/SIGHUP too. Siblings of
// the same name left by a process that no longer runs are removed on construction. Checking whether `file` may
// be replaced is the command's (inputConflict and its own rule), before any work.
class TemporaryOutputFile
{
public:
  explicit TemporaryOutputFile(const std::filesystem::path& file);
  ~TemporaryOutputFile(); // removes the temporary file unless committed
  TemporaryOutputFile(const TemporaryOutputFile&) = delete;
  TemporaryOutputFile& operator=(const TemporaryOutputFile&) = delete;

  const std::filesystem::path& path() const { return temporary_; }
  void commit(); // throws InputError naming the file when the rename fails

private:
  std::filesystem::path file_;
  std::filesystem::path temporary_;
  bool committed_ = false;
};

// Implementation of writeDirectoryAtomically; not for direct use.
class TemporaryOutput
{
public:
  explicit TemporaryOutput(const OutputTarget& target); // checks the target, cleans stale siblings, creates
  ~TemporaryOutput();                                   // removes the temporary directory unless committed
  TemporaryOutput(const TemporaryOutput&) = delete;
  TemporaryOutput& operator=(const TemporaryOutput&) = delete;

  const std::filesystem::path& path() const { return temporary_; }
  void commit(); // the temporary directory takes the place of the target
  // `error` with the temporary directory's path replaced by --out's, as the user knows it.
  InputError namedForUser(const InputError& error) const;

private:
  OutputTarget target_;
  std::filesystem::path resolved_;  // target.dir, absolute, symbolic links resolved
  std::filesystem::path temporary_; // the sibling being written
  bool committed_ = false;
};

template <typename WriteFiles>
void writeDirectoryAtomically(const OutputTarget& target, WriteFiles writeFiles)
{
  TemporaryOutput output(target);
  try
  {
    writeFiles(output.path());
  }
  catch (const InputError& error)
  {
    throw output.namedForUser(error);
  }
  output.commit();
}

} // namespace sl
