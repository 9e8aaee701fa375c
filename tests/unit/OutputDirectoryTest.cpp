// The output contract (io/OutputDirectory.h) without the executable: the protected home directories, asked only
// whether a target would be refused (checkOutputTarget never writes, so a regression cannot touch a real home),
// and TemporaryOutputFile's clean-up in a directory of the test's own.
#include "core/Error.h"
#include "io/OutputDirectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <pwd.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace sl
{
namespace
{

namespace fs = std::filesystem;

// HOME as the test found it, restored when the test ends.
class HomeEnvironment
{
public:
  HomeEnvironment()
  {
    if (const char* home = std::getenv("HOME"))
    {
      saved_ = home;
    }
  }
  ~HomeEnvironment()
  {
    if (saved_)
    {
      ::setenv("HOME", saved_->c_str(), 1);
    }
    else
    {
      ::unsetenv("HOME");
    }
  }

private:
  std::optional<std::string> saved_;
};

fs::path passwordDatabaseHome()
{
  const struct passwd* entry = ::getpwuid(::getuid());
  return entry && entry->pw_dir ? fs::path(entry->pw_dir) : fs::path();
}

bool listed(const std::vector<fs::path>& homes, const fs::path& home)
{
  const fs::path resolved = fs::weakly_canonical(home);
  return std::find(homes.begin(), homes.end(), resolved) != homes.end();
}

TEST(OutputDirectory, TheHomeFromThePasswordDatabaseIsProtectedWithHomeUnset)
{
  const fs::path home = passwordDatabaseHome();
  ASSERT_FALSE(home.empty()) << "no password database entry for uid " << ::getuid();
  const HomeEnvironment restore;
  ::unsetenv("HOME");
  EXPECT_TRUE(listed(protectedHomeDirectories(), home)) << home;
  // `shadowlab render ... -o ~ --force` with HOME unset: the shell expands ~ from the password database.
  for (const fs::path& out : { home, home / "." })
  {
    try
    {
      checkOutputTarget({ out, "render", true, {} });
      ADD_FAILURE() << "--out " << out << " --force was not refused with HOME unset";
    }
    catch (const InputError& error)
    {
      EXPECT_NE(std::string(error.what()).find("home directory"), std::string::npos) << error.what();
    }
  }
  ::setenv("HOME", "", 1); // empty: the same
  EXPECT_TRUE(listed(protectedHomeDirectories(), home)) << home;
}

TEST(OutputDirectory, HomeAndThePasswordDatabaseHomeAreBothProtected)
{
  const fs::path home = passwordDatabaseHome();
  ASSERT_FALSE(home.empty());
  const HomeEnvironment restore;
  const fs::path elsewhere = fs::temp_directory_path();
  ::setenv("HOME", elsewhere.c_str(), 1);
  const std::vector<fs::path> homes = protectedHomeDirectories();
  EXPECT_TRUE(listed(homes, elsewhere));
  EXPECT_TRUE(listed(homes, home));
  EXPECT_THROW(checkOutputTarget({ elsewhere, "render", true, {} }), InputError);
  EXPECT_THROW(checkOutputTarget({ home, "render", true, {} }), InputError);
}

TEST(OutputDirectory, TemporaryOutputFileRemovesStaleSiblingsAndItselfUnlessCommitted)
{
  const fs::path dir = fs::temp_directory_path() / ("shadowlab-unit-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const pid_t dead = ::fork();
  if (dead == 0)
  {
    ::_exit(0);
  }
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  const fs::path stale = dir / (".m.png.shadowlab-partial-" + std::to_string(dead));
  const fs::path otherName = dir / (".n.png.shadowlab-partial-" + std::to_string(dead));
  std::ofstream(stale) << "half";
  std::ofstream(otherName) << "half";
  fs::path temporary;
  {
    TemporaryOutputFile output(dir / "m.png");
    temporary = output.path();
    EXPECT_FALSE(fs::exists(stale)) << "a dead process's partial file was left";
    EXPECT_TRUE(fs::exists(otherName)) << "another output's partial file was removed";
    std::ofstream(temporary) << "not committed";
  }
  EXPECT_FALSE(fs::exists(temporary)) << "an uncommitted temporary file was left";
  EXPECT_FALSE(fs::exists(dir / "m.png"));
  {
    TemporaryOutputFile output(dir / "m.png");
    std::ofstream(output.path()) << "complete";
    output.commit();
  }
  std::ifstream written(dir / "m.png");
  std::string text;
  written >> text;
  EXPECT_EQ(text, "complete");
  fs::remove_all(dir);
}

} // namespace
} // namespace sl
