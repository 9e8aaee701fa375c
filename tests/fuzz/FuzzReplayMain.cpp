// Replays a fuzz target's corpus without libFuzzer, so the normal (gcc) build and CI check every committed
// input, found crashes included, on each run: fuzz_replay_<target> <dir or file>...
//
// Every regular file under the arguments (recursively, in sorted order so a failure names the same file every
// time) goes through the target's LLVMFuzzerTestOneInput once. An exception escaping it is a failure: the
// target already swallows InputError, so whatever arrives here is another kind. A crash or abort ends the
// process, which CTest reports as a failure; the name of the file being replayed is printed before each input
// so the log says which one it was. Exit 0 only when every input passed and at least one was found (an empty
// or mistyped corpus path must not pass silently).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{

std::vector<std::filesystem::path> inputsUnder(const std::filesystem::path& root)
{
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_regular_file(root))
    files.push_back(root);
  else if (std::filesystem::is_directory(root))
  {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    {
      if (entry.is_regular_file())
        files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> readBytes(const std::filesystem::path& file)
{
  std::ifstream stream(file, std::ios::binary);
  return { std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>() };
}

} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s <corpus dir or file>...\n", argv[0]);
    return 2;
  }
  std::size_t replayed = 0;
  std::size_t failed = 0;
  for (int a = 1; a < argc; ++a)
  {
    const std::vector<std::filesystem::path> files = inputsUnder(argv[a]);
    if (files.empty())
    {
      std::fprintf(stderr, "FAIL %s: no inputs there\n", argv[a]);
      ++failed;
    }
    for (const std::filesystem::path& file : files)
    {
      const std::vector<std::uint8_t> bytes = readBytes(file);
      std::fprintf(stderr, "replay %s (%zu bytes)\n", file.c_str(), bytes.size());
      std::fflush(stderr);
      try
      {
        LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      }
      catch (const std::exception& error)
      {
        std::fprintf(stderr, "FAIL %s: exception other than InputError: %s\n", file.c_str(), error.what());
        ++failed;
      }
      catch (...)
      {
        std::fprintf(stderr, "FAIL %s: non-standard exception\n", file.c_str());
        ++failed;
      }
      ++replayed;
    }
  }
  std::fprintf(stderr, "replayed %zu inputs, %zu failed\n", replayed, failed);
  return failed == 0 ? 0 : 1;
}
