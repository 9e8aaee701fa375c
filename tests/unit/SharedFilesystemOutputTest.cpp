// The output contract on a shared filesystem (issue 32): a temporary sibling is another process's only on the host
// that made it, so a run removes a dead writer's sibling only when its marker names this host.
#include "io/OutputDirectory.h"
#include "support/CliRun.h"
#include "support/TempDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

namespace sl
{
namespace
{

// A process id that no longer runs: a child that has exited and been reaped.
pid_t sharedFilesystemDeadPid()
{
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

std::string sharedFilesystemHostName()
{
  char name[256] = {};
  ::gethostname(name, sizeof(name) - 1);
  return name;
}

TEST(SharedFilesystemOutput, ADeadWritersSiblingIsRemovedOnlyOnItsOwnHost)
{
  const test::TempDir temp;
  const pid_t dead = sharedFilesystemDeadPid();
  const auto sibling = [&](const std::string& host, int n) {
    const std::filesystem::path dir =
      temp.path() / (".shadowlab-partial-" + std::to_string(dead) + "-" + std::to_string(n));
    std::filesystem::create_directories(dir);
    test::writeFile(dir / kOutputMarkerName,
      nlohmann::json{ { "tool", "shadowlab" }, { "command", "reference" }, { "pid", dead }, { "host", host } }.dump());
    return dir;
  };
  const std::filesystem::path here = sibling(sharedFilesystemHostName(), 0);
  const std::filesystem::path elsewhere = sibling("another-node-of-the-cluster", 1);
  writeDirectoryAtomically(OutputTarget{ temp.path() / "out", "reference", false, {} },
    [](const std::filesystem::path& dir) { test::writeFile(dir / "a.txt", "a"); });
  EXPECT_FALSE(std::filesystem::exists(here)) << "a dead writer's sibling of this host is stale";
  EXPECT_TRUE(std::filesystem::exists(elsewhere)) << "pid " << dead << " means nothing for another node's writer";
  const nlohmann::json marker = nlohmann::json::parse(test::readFile(temp.path() / "out" / kOutputMarkerName));
  EXPECT_EQ(marker.at("host").get<std::string>(), sharedFilesystemHostName());
}

} // namespace
} // namespace sl
