// The GLSL sources embedded at build time (cmake/Shaders.cmake generates the table).
#pragma once

#include <string>
#include <vector>

namespace sl
{

struct EmbeddedShader
{
  std::string path;   // relative to shaders/, e.g. "common/ShadowMapCommon.glsl"
  const char* source; // the file's text
};

const std::vector<EmbeddedShader>& embeddedShaders();

} // namespace sl
