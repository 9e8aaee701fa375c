#include "gl/ShaderLibrary.h"

#include "core/Error.h"
#include "gl/ShaderTable.h"

#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace sl
{
namespace
{

const std::map<std::string, std::string>& shaderTexts()
{
  static const std::map<std::string, std::string> texts = [] {
    std::map<std::string, std::string> byPath;
    for (const EmbeddedShader& shader : embeddedShaders())
    {
      byPath.emplace(shader.path, shader.source);
    }
    return byPath;
  }();
  return texts;
}

void expandIncludes(const std::string& path, std::set<std::string>& included, std::ostringstream& out)
{
  if (!included.insert(path).second)
  {
    return;
  }
  static const std::regex includeLine(R"(^\s*#include\s+"([^"]+)\"\s*$)");
  std::istringstream lines(embeddedShaderText(path));
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line))
  {
    ++lineNumber;
    std::smatch match;
    if (std::regex_match(line, match, includeLine))
    {
      out << "// begin " << match[1] << "\n";
      expandIncludes(match[1], included, out);
      out << "// end " << match[1] << " (back in " << path << ":" << lineNumber << ")\n";
    }
    else
    {
      out << line << "\n";
    }
  }
}

} // namespace

const std::string& embeddedShaderText(const std::string& path)
{
  const auto& texts = shaderTexts();
  const auto found = texts.find(path);
  if (found == texts.end())
  {
    throw GraphicsError(format("shader '", path, "' is not embedded (list it in shaders/shaders.cmake or in its technique's technique.cmake)"));
  }
  return found->second;
}

std::string assembleShader(const std::string& path, const ShaderDefines& defines, const std::string& declarations)
{
  std::ostringstream out;
  out << "#version 450 core\n";
  for (const auto& [name, value] : defines)
  {
    out << "#define " << name << (value.empty() ? "" : " ") << value << "\n";
  }
  out << declarations;
  out << "// file " << path << "\n";
  std::set<std::string> included;
  expandIncludes(path, included, out);
  return out.str();
}

} // namespace sl
