// A fresh directory under the system temp dir, removed with everything in it when the test ends. Names are
// unique across the parallel processes ctest runs.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

namespace sl::test
{

class TempDir
{
public:
  TempDir()
  {
    static std::atomic<int> counter{ 0 };
    const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
      ("shadowlab-test-" + std::to_string(std::random_device{}()) + "-" + std::to_string(now) + "-" +
        std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir()
  {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Writes `content` to path() / name; a test failure when it cannot.
  std::filesystem::path write(const std::string& name, const std::string& content) const
  {
    const std::filesystem::path file = path_ / name;
    std::ofstream stream(file, std::ios::binary);
    stream.write(content.data(), static_cast<std::streamsize>(content.size()));
    EXPECT_TRUE(stream.good()) << "could not write " << file;
    return file;
  }

private:
  std::filesystem::path path_;
};

} // namespace sl::test
