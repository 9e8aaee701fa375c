// The output contract (see OutputDirectory.h and docs/outputs.md).
#include "io/OutputDirectory.h"

#include "core/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

constexpr const char* kPartialPrefix = ".shadowlab-partial-";

// ---- what a signal handler needs: plain data, written with signals blocked ---------------------------------

char g_temporaryPath[PATH_MAX];             // the temporary directory being written, "" when none
char g_doomedPath[PATH_MAX];                // where the handler moves it before removing it
std::atomic<int> g_pathChanging{ 0 };       // 1 inside a CleanupPathSection
static_assert(std::atomic<int>::is_always_lock_free, "read in a signal handler");
volatile std::sig_atomic_t g_childPid = 0;  // the child a signal is forwarded to (bench), 0 when none
constexpr int kHandledSignals[] = { SIGINT, SIGTERM, SIGHUP };

// Removes the directory tree `name` under `parentFd` with async-signal-safe calls only (openat, getdents64,
// unlinkat, close): a signal handler may not call std::filesystem (it allocates). Symbolic links are removed,
// never followed. Output trees are two levels deep; the depth bound only stops a pathological tree.
void removeTreeSignalSafe(int parentFd, const char* name, int depth)
{
  const int fd = ::openat(parentFd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0 && errno == ENOTDIR && depth == 0)
  {
    ::unlinkat(parentFd, name, 0); // a temporary file (TemporaryOutputFile), not a directory
    return;
  }
  if (fd >= 0)
  {
    alignas(8) char buffer[4096];
    // Removing entries while reading a directory may skip some: read it again until a pass removes nothing.
    for (int pass = 0; pass < 64; ++pass)
    {
      bool removedAny = false;
      ::lseek(fd, 0, SEEK_SET);
      for (;;)
      {
        const ssize_t bytes = ::getdents64(fd, buffer, sizeof(buffer));
        if (bytes <= 0)
        {
          break;
        }
        for (ssize_t offset = 0; offset < bytes;)
        {
          const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + offset);
          offset += entry->d_reclen;
          const char* child = entry->d_name;
          if ((child[0] == '.' && child[1] == '\0') || (child[0] == '.' && child[1] == '.' && child[2] == '\0'))
          {
            continue;
          }
          if (::unlinkat(fd, child, 0) == 0)
          {
            removedAny = true;
          }
          else if ((errno == EISDIR || errno == EPERM) && depth < 16)
          {
            removeTreeSignalSafe(fd, child, depth + 1);
            removedAny = true;
          }
        }
      }
      if (!removedAny)
      {
        break;
      }
    }
    ::close(fd);
  }
  ::unlinkat(parentFd, name, AT_REMOVEDIR);
}

extern "C" void handleTerminatingSignal(int signalNumber)
{
  const int savedErrno = errno;
  const pid_t child = static_cast<pid_t>(g_childPid);
  if (child > 0)
  {
    ::kill(child, signalNumber);
  }
  // Wait (at most a second) for a section on another thread that is creating or unregistering the directory.
  for (int waited = 0; g_pathChanging.load() != 0 && waited < 1000; ++waited)
  {
    const struct timespec millisecond = { 0, 1000000 };
    ::nanosleep(&millisecond, nullptr);
  }
  if (g_temporaryPath[0] != '\0')
  {
    // The handler may run on any thread while the main thread goes on writing into the directory by path.
    // Moved away first, the directory can only lose entries: new files by the old path fail to be created.
    // (The moved name still matches the stale-sibling pattern, should the process die before it is gone.)
    const bool moved = ::rename(g_temporaryPath, g_doomedPath) == 0;
    removeTreeSignalSafe(AT_FDCWD, moved ? g_doomedPath : g_temporaryPath, 0);
  }
  // End the process with the signal, as if it had not been caught (the shell reports 128 + signal).
  std::signal(signalNumber, SIG_DFL);
  errno = savedErrno;
  ::raise(signalNumber);
}

// A section in which the temporary directory and its registration for the handler change together (created and
// registered, or unregistered). The handled signals are blocked on this thread; a signal delivered meanwhile to
// another thread (llvmpipe's, Embree's) waits in the handler until the section ends, so the handler never misses
// a directory that exists, nor reads half a path.
class CleanupPathSection
{
public:
  CleanupPathSection()
  {
    sigset_t blocked;
    sigemptyset(&blocked);
    for (const int signalNumber : kHandledSignals)
    {
      sigaddset(&blocked, signalNumber);
    }
    ::pthread_sigmask(SIG_BLOCK, &blocked, &previous_);
    g_pathChanging.store(1);
  }
  ~CleanupPathSection()
  {
    g_pathChanging.store(0);
    ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
  }
  CleanupPathSection(const CleanupPathSection&) = delete;
  CleanupPathSection& operator=(const CleanupPathSection&) = delete;

private:
  sigset_t previous_;
};

// Sets the path the handler removes; call inside a CleanupPathSection.
void setSignalCleanupPath(const std::string& path)
{
  const std::string doomed = path.empty() ? path : path + "-interrupted";
  if (doomed.size() >= sizeof(g_doomedPath))
  {
    g_temporaryPath[0] = '\0'; // longer than any path the system accepts: nothing to clean
    return;
  }
  std::memcpy(g_doomedPath, doomed.c_str(), doomed.size() + 1);
  std::memcpy(g_temporaryPath, path.c_str(), path.size() + 1);
}

// ---- paths ----------------------------------------------------------------------------------------------

// --out as an absolute, normal path with symbolic links resolved in the part that exists (so "-o .", "-o x/..",
// a trailing slash and a link to a directory all name the directory they mean).
fs::path resolveOutputPath(const fs::path& dir)
{
  if (dir.empty())
  {
    throw InputError("--out: empty path; name a directory for the results");
  }
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(dir, error), error);
  if (error)
  {
    throw InputError(format("--out ", dir.string(), ": cannot resolve the path (", error.message(), ")"));
  }
  resolved = resolved.lexically_normal();
  if (resolved.filename().empty() && resolved.has_parent_path() && resolved != resolved.root_path())
  {
    resolved = resolved.parent_path();
  }
  return resolved;
}

fs::path resolveInputPath(const fs::path& input)
{
  std::error_code error;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(input, error), error);
  return error ? fs::absolute(input).lexically_normal() : resolved.lexically_normal();
}

// True when `ancestor` is `path` or one of its ancestors (both absolute and normal).
bool isAncestorOrSelf(const fs::path& ancestor, const fs::path& path)
{
  auto a = ancestor.begin();
  auto p = path.begin();
  for (; a != ancestor.end(); ++a, ++p)
  {
    if (a->empty() && std::next(a) == ancestor.end())
    {
      break; // a trailing separator
    }
    if (p == path.end() || *a != *p)
    {
      return false;
    }
  }
  return true;
}

bool hasMarker(const fs::path& dir)
{
  std::error_code error;
  const fs::path marker = dir / kOutputMarkerName;
  if (!fs::is_regular_file(fs::symlink_status(marker, error)))
  {
    return false;
  }
  std::FILE* file = std::fopen(marker.c_str(), "rb");
  if (!file)
  {
    return false;
  }
  char text[4096];
  const std::size_t bytes = std::fread(text, 1, sizeof(text), file);
  std::fclose(file);
  const nlohmann::json document = nlohmann::json::parse(text, text + bytes, nullptr, false);
  return document.is_object() && document.value("tool", std::string()) == "shadowlab";
}

bool isEmptyDirectory(const fs::path& dir)
{
  std::error_code error;
  const fs::directory_iterator first(dir, error);
  if (error)
  {
    throw InputError(format("--out ", dir.string(), ": cannot list the existing directory (", error.message(), ")"));
  }
  return first == fs::directory_iterator();
}

// Why `resolved` may never be replaced, even with --force; empty when it may.
std::string protectedReason(const fs::path& resolved, const OutputTarget& target)
{
  if (resolved == resolved.root_path())
  {
    return "is the filesystem root";
  }
  std::error_code error;
  const fs::path cwd = fs::current_path(error);
  if (!error && isAncestorOrSelf(resolved, resolveInputPath(cwd)))
  {
    return resolved == resolveInputPath(cwd) ? "is the current directory" : "holds the current directory";
  }
  for (const fs::path& home : protectedHomeDirectories())
  {
    if (isAncestorOrSelf(resolved, home))
    {
      return "is or holds the home directory";
    }
  }
  return inputConflict(resolved, target.inputs);
}

std::string timestamp()
{
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// This machine's name, as the marker records it: a process id means something only on the host that made it.
std::string thisHostName()
{
  char name[HOST_NAME_MAX + 1] = {};
  return ::gethostname(name, sizeof(name) - 1) == 0 ? std::string(name) : std::string();
}

// Whether the temporary sibling `dir` was made on this host (its marker's "host"; a marker without one predates
// the field and was written here). On a shared filesystem another node's live writer has a process id that means
// nothing here: its sibling must not be taken for a dead process's (issue 32).
bool madeOnThisHost(const fs::path& dir)
{
  std::ifstream file(dir / kOutputMarkerName);
  try
  {
    const nlohmann::json marker = nlohmann::json::parse(file);
    return !marker.contains("host") || marker["host"] == thisHostName();
  }
  catch (const nlohmann::json::exception&)
  {
    return false;
  }
}

// Temporary siblings left by a process that no longer runs (SIGKILL, a crash, power loss) and that carry the
// marker (so they are ShadowLab's): removed. A live process's sibling (another run writing the same --out) is
// left alone.
void removeStaleSiblings(const fs::path& parent)
{
  std::error_code error;
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error))
  {
    const std::string name = it->path().filename().string();
    if (name.rfind(kPartialPrefix, 0) != 0 || !fs::is_directory(it->symlink_status(error)))
    {
      continue;
    }
    char* endOfPid = nullptr;
    const long pid = std::strtol(name.c_str() + std::strlen(kPartialPrefix), &endOfPid, 10);
    if (pid <= 0 || *endOfPid != '-' || pid == ::getpid())
    {
      continue;
    }
    const bool processGone = ::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH;
    if (processGone && hasMarker(it->path()) && madeOnThisHost(it->path()))
    {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

// Temporary files `.<name>.shadowlab-partial-<pid>` of `file` left by a process that no longer runs: removed.
// The name says whose they are (no marker fits in a PNG); other names, links and live processes' are left alone.
void removeStaleFileSiblings(const fs::path& file)
{
  const fs::path parent = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const std::string prefix = "." + file.filename().string() + kPartialPrefix;
  std::error_code error;
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error))
  {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !fs::is_regular_file(it->symlink_status(error)))
    {
      continue;
    }
    const std::string pidText = name.substr(prefix.size());
    char* endOfPid = nullptr;
    const long pid = std::strtol(pidText.c_str(), &endOfPid, 10);
    if (pidText.empty() || pid <= 0 || *endOfPid != '\0' || pid == ::getpid())
    {
      continue;
    }
    if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH)
    {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

void removeQuietly(const fs::path& path)
{
  std::error_code ignored;
  fs::remove_all(path, ignored);
}

std::string systemReason(int errorNumber)
{
  return std::strerror(errorNumber);
}

} // namespace

std::string inputConflict(const fs::path& output, const std::vector<fs::path>& inputs)
{
  const fs::path resolved = resolveInputPath(output);
  std::error_code error;
  for (const fs::path& input : inputs)
  {
    const fs::path resolvedInput = resolveInputPath(input);
    if (resolved == resolvedInput)
    {
      return "is " + input.string() + ", an input of this command";
    }
    if (isAncestorOrSelf(resolved, resolvedInput))
    {
      return "holds " + input.string() + ", an input of this command";
    }
    if (fs::is_directory(resolvedInput, error) && isAncestorOrSelf(resolvedInput, resolved))
    {
      return "lies inside " + input.string() + ", an input directory of this command";
    }
  }
  return {};
}

std::vector<fs::path> protectedHomeDirectories()
{
  std::vector<fs::path> homes;
  const auto add = [&homes](const char* home) {
    if (home && *home)
    {
      const fs::path resolved = resolveInputPath(home);
      if (std::find(homes.begin(), homes.end(), resolved) == homes.end())
      {
        homes.push_back(resolved);
      }
    }
  };
  add(std::getenv("HOME"));
  // With HOME unset (env -u HOME, cron, some services) a shell still expands ~ from the password database.
  std::vector<char> buffer(16384);
  struct passwd entry
  {
  };
  struct passwd* found = nullptr;
  if (::getpwuid_r(::getuid(), &entry, buffer.data(), buffer.size(), &found) == 0 && found)
  {
    add(found->pw_dir);
  }
  return homes;
}

void checkOutputTarget(const OutputTarget& target)
{
  const fs::path resolved = resolveOutputPath(target.dir);
  const std::string named = "--out " + target.dir.string();
  if (const std::string reason = protectedReason(resolved, target); !reason.empty())
  {
    throw InputError(format(named, ": refused, it ", reason, " (nothing was written)"));
  }
  std::error_code error;
  const fs::file_status status = fs::status(resolved, error);
  if (!fs::exists(status))
  {
    return;
  }
  if (!fs::is_directory(status))
  {
    throw InputError(named + ": exists and is not a directory");
  }
  if (!target.force && !hasMarker(resolved) && !isEmptyDirectory(resolved))
  {
    throw InputError(format(named, ": refused, the directory exists and was not written by shadowlab (no ",
      kOutputMarkerName, " in it); choose another --out, or add --force to replace it"));
  }
}

void writeFileChecked(const fs::path& path, const std::string& bytes)
{
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
  {
    throw InputError(format(path.string(), ": cannot write (", systemReason(errno), ")"));
  }
  std::size_t written = 0;
  while (written < bytes.size())
  {
    const ssize_t count = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (count < 0 && errno == EINTR)
    {
      continue;
    }
    if (count <= 0)
    {
      const int reason = count < 0 ? errno : EIO;
      ::close(fd);
      throw InputError(format(path.string(), ": cannot write (", systemReason(reason), ")"));
    }
    written += static_cast<std::size_t>(count);
  }
  if (::close(fd) != 0)
  {
    throw InputError(format(path.string(), ": cannot write (", systemReason(errno), ")"));
  }
}

void installOutputSignalHandlers()
{
  // A write past the file size limit (ulimit -f) would kill the process with SIGXFSZ and leave the temporary
  // directory behind; ignored, the write fails with EFBIG and is reported like a full disk (children inherit it).
  std::signal(SIGXFSZ, SIG_IGN);
  struct sigaction action
  {
  };
  action.sa_handler = handleTerminatingSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int signalNumber : kHandledSignals)
  {
    struct sigaction previous
    {
    };
    // A signal the caller ignores (nohup, a background job's SIGINT) stays ignored.
    if (::sigaction(signalNumber, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
    {
      continue;
    }
    ::sigaction(signalNumber, &action, nullptr);
  }
}

void setForegroundChild(int pid)
{
  g_childPid = pid;
}

TemporaryOutput::TemporaryOutput(const OutputTarget& target)
  : target_(target)
  , resolved_(resolveOutputPath(target.dir))
{
  checkOutputTarget(target_);
  SL_CHECK_MSG(g_temporaryPath[0] == '\0', "one output directory at a time per process");
  const fs::path parent = resolved_.parent_path();
  std::error_code error;
  fs::create_directories(parent, error);
  if (error)
  {
    throw InputError(format("--out ", target_.dir.string(), ": cannot create ", parent.string(), " (",
      error.message(), ")"));
  }
  removeStaleSiblings(parent);
  static std::atomic<int> counter{ 0 };
  for (int attempt = 0; temporary_.empty(); ++attempt)
  {
    const fs::path candidate = parent / format(kPartialPrefix, ::getpid(), "-", counter++);
    const CleanupPathSection section;
    if (::mkdir(candidate.c_str(), 0755) == 0)
    {
      temporary_ = candidate;
      setSignalCleanupPath(temporary_.string());
    }
    else if (errno != EEXIST || attempt > 1000)
    {
      throw InputError(format("--out ", target_.dir.string(), ": cannot create a directory next to it (",
        systemReason(errno), ")"));
    }
  }
  // The marker goes in first, so even a sibling left by a killed run is recognisably ShadowLab's.
  const nlohmann::json marker = { { "tool", "shadowlab" }, { "command", target_.command },
    { "version", SL_VERSION }, { "created", timestamp() }, { "pid", ::getpid() },
    { "host", thisHostName() } };
  try
  {
    writeFileChecked(temporary_ / kOutputMarkerName, marker.dump(2) + "\n");
  }
  catch (...)
  {
    removeQuietly(temporary_);
    const CleanupPathSection section;
    setSignalCleanupPath("");
    throw;
  }
}

TemporaryOutput::~TemporaryOutput()
{
  if (!committed_)
  {
    removeQuietly(temporary_);
  }
  const CleanupPathSection section;
  setSignalCleanupPath("");
}

InputError TemporaryOutput::namedForUser(const InputError& error) const
{
  std::string message = error.what();
  const std::string temporary = temporary_.string();
  const std::string shown = target_.dir.string();
  for (std::size_t at = message.find(temporary); at != std::string::npos; at = message.find(temporary, at + shown.size()))
  {
    message.replace(at, temporary.size(), shown);
  }
  return InputError(message);
}

void TemporaryOutput::commit()
{
  // The target may have changed while the results were computed (another run, the user): decide again.
  checkOutputTarget(target_);
  const std::string named = "--out " + target_.dir.string();
  if (::rename(temporary_.c_str(), resolved_.c_str()) == 0)
  {
    committed_ = true; // there was nothing (or an empty directory) in the way
    return;
  }
  if (errno != EEXIST && errno != ENOTEMPTY)
  {
    throw InputError(format(named, ": cannot move the results into place (", systemReason(errno), ")"));
  }
  // Swap the finished results and the previous output in one step, so --out is never missing or half
  // written; the previous output (now at the temporary path) is then removed.
  if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, resolved_.c_str(), RENAME_EXCHANGE) != 0)
  {
    if (errno != EINVAL && errno != ENOSYS)
    {
      throw InputError(format(named, ": cannot replace the previous results (", systemReason(errno), ")"));
    }
    // A filesystem without atomic exchange: move the previous output aside, then the results in.
    const fs::path aside = fs::path(temporary_.string() + "-previous");
    if (::rename(resolved_.c_str(), aside.c_str()) != 0)
    {
      throw InputError(format(named, ": cannot replace the previous results (", systemReason(errno), ")"));
    }
    if (::rename(temporary_.c_str(), resolved_.c_str()) != 0)
    {
      const int reason = errno;
      ::rename(aside.c_str(), resolved_.c_str());
      throw InputError(format(named, ": cannot move the results into place (", systemReason(reason), ")"));
    }
    committed_ = true;
    removeQuietly(aside);
    return;
  }
  committed_ = true;
  removeQuietly(temporary_);
}

TemporaryOutputFile::TemporaryOutputFile(const fs::path& file)
  : file_(file)
{
  SL_CHECK_MSG(g_temporaryPath[0] == '\0', "one output at a time per process");
  removeStaleFileSiblings(file_);
  const fs::path parent = file_.has_parent_path() ? file_.parent_path() : fs::path(".");
  // Absolute: the signal handler removes it by this path whatever the current directory is by then.
  temporary_ = fs::absolute(parent / ("." + file_.filename().string() + kPartialPrefix + std::to_string(::getpid())));
  const CleanupPathSection section;
  setSignalCleanupPath(temporary_.string());
}

TemporaryOutputFile::~TemporaryOutputFile()
{
  if (!committed_)
  {
    std::error_code ignored;
    fs::remove(temporary_, ignored);
  }
  const CleanupPathSection section;
  setSignalCleanupPath("");
}

void TemporaryOutputFile::commit()
{
  if (::rename(temporary_.c_str(), file_.c_str()) != 0)
  {
    throw InputError(format(file_.string(), ": cannot write (", systemReason(errno), ")"));
  }
  committed_ = true;
}

} // namespace sl
