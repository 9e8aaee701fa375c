// Shared pieces of the libFuzzer targets (tests/fuzz/*FuzzTarget.cpp).
//
// Each target defines LLVMFuzzerTestOneInput. An sl::InputError is the normal answer to a bad input and is
// swallowed there; anything else (another exception, an abort, a failed expect(), a sanitizer
// report) is a crash. The same function runs under libFuzzer (clang, -DSL_FUZZ=ON) and under
// FuzzReplayMain.cpp (any compiler, CTest), which replays the committed corpus.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace sl::fuzz
{

// A broken promise of the code under test (not a bad input): print it and abort, so libFuzzer records the
// input as a crash and the replay driver's ctest case fails.
[[noreturn]] inline void fail(const std::string& what)
{
  std::fprintf(stderr, "fuzz target: %s\n", what.c_str());
  std::abort();
}

inline void expect(bool condition, const std::string& what)
{
  if (!condition)
    fail(what);
}

// A directory of this process's own, for readers that take a path and not bytes. Per process because
// libFuzzer's -jobs/-fork workers and parallel ctest runs share /tmp; removed when the process exits normally
// (a crashing run leaves it, which is what one wants when looking at the crash).
class ScratchDirectory
{
public:
  ScratchDirectory()
    : path_(std::filesystem::temp_directory_path() / ("shadowlab-fuzz-" + std::to_string(::getpid())))
  {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory()
  {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Writes `size` bytes to `name` inside the directory, replacing the previous input, and returns its path.
  std::filesystem::path write(const std::string& name, const std::uint8_t* data, std::size_t size) const
  {
    // Created again if something (a /tmp cleaner) removed it meanwhile: a missing directory is not a finding.
    std::error_code ignored;
    std::filesystem::create_directories(path_, ignored);
    const std::filesystem::path file = path_ / name;
    std::ofstream stream(file, std::ios::binary | std::ios::trunc);
    stream.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    stream.close();
    if (!stream)
      fail("cannot write the fuzz input to " + file.string());
    return file;
  }

private:
  std::filesystem::path path_;
};

} // namespace sl::fuzz
