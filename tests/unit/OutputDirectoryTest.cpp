// The output contract's protected directories (io/OutputDirectory.h), checked without the executable: these
// tests only ask whether a target would be refused (checkOutputTarget never writes), so a regression cannot
// touch a real home directory.
#include "core/Error.h"
#include "io/OutputDirectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <pwd.h>
#include <string>
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

} // namespace
} // namespace sl
