// The shadowlab subcommands. Each returns the process exit code; user errors are thrown as InputError
// and reported once by main().
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace sl
{

struct RenderOptions
{
  std::string sceneFile;
  std::string technique = "pcf";
  std::vector<std::string> settings;
  std::string resolution; // "WxH" or empty
  std::string outDir = "out";
  int lightIndex = 0;
  bool quiet = false;
};

int runRender(const RenderOptions& options, std::ostream& log);
int runList(bool asJson, std::ostream& out);

} // namespace sl
