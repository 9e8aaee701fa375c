// The shadowlab executable (SL_SHADOWLAB_EXE) run as a subprocess in a working directory, with its exit code,
// stdout and stderr: what the CLI suites assert on. The tests' one way to run shadowlab to completion (the
// signal tests in OutputSafetyTest.cpp fork and exec it themselves, to signal it mid-run). Header-only.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace sl::test
{

inline std::string readFile(const std::filesystem::path& path)
{
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

inline void writeFile(const std::filesystem::path& path, const std::string& content)
{
  std::ofstream stream(path, std::ios::binary);
  stream << content;
  ASSERT_TRUE(stream.good()) << "could not write " << path;
}

// Single-quoted for /bin/sh.
inline std::string shellQuote(const std::string& argument)
{
  std::string quoted = "'";
  for (char c : argument)
  {
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return quoted + "'";
}

struct RunResult
{
  int exitCode = -1;   // the exit status; 128 + n when the process ended with signal n
  std::string out;
  std::string err;
  std::string commandLine;

  std::size_t errLines() const { return static_cast<std::size_t>(std::count(err.begin(), err.end(), '\n')); }
  // For failure messages.
  std::string describe() const
  {
    return "command: " + commandLine + "\nexit: " + std::to_string(exitCode) + "\nstderr:\n" + err +
      "\nstdout (first 2000 chars):\n" + out.substr(0, 2000);
  }
};

// Runs shadowlab with `arguments` in `workDir`, after the shell commands in `prelude` (variable assignments,
// ulimit, trap), stdout and stderr captured to files outside workDir.
inline RunResult runShadowlabIn(const std::vector<std::string>& arguments, const std::filesystem::path& workDir,
  const std::string& prelude = "")
{
  RunResult result;
  const std::filesystem::path captureDir = workDir.parent_path();
  const std::string stem = ".capture-" + workDir.filename().string();
  const std::filesystem::path outFile = captureDir / (stem + ".stdout");
  const std::filesystem::path errFile = captureDir / (stem + ".stderr");
  std::string command = "cd " + shellQuote(workDir.string()) + " && " + (prelude.empty() ? "" : prelude + "; ") +
    "exec " + shellQuote(SL_SHADOWLAB_EXE);
  for (const std::string& argument : arguments)
  {
    command += " " + shellQuote(argument);
  }
  result.commandLine = command;
  command = "(" + command + ") >" + shellQuote(outFile.string()) + " 2>" + shellQuote(errFile.string()) +
    " </dev/null";
  const int status = std::system(command.c_str());
  result.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  result.out = readFile(outFile);
  result.err = readFile(errFile);
  std::error_code ignored;
  std::filesystem::remove(outFile, ignored);
  std::filesystem::remove(errFile, ignored);
  return result;
}

// The names in `dir`, sorted.
inline std::vector<std::string> entriesOf(const std::filesystem::path& dir)
{
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
  {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string joined(const std::vector<std::string>& names)
{
  std::string text;
  for (const std::string& name : names)
  {
    text += (text.empty() ? "" : ", ") + name;
  }
  return text;
}

} // namespace sl::test
