// Assembles GLSL programs from the embedded shader files.
//
// A stage file may contain `#include "common/LightModel.glsl"` lines; they are replaced by that file's text
// (recursively, each file at most once per stage, like #pragma once). The `#version` line and a block of
// `#define`s generated from C++ (technique variants, output locations) are prepended, so constants are
// never kept in sync by hand between C++ and GLSL (the house style).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sl
{

using ShaderDefines = std::vector<std::pair<std::string, std::string>>; // name, value ("" for flags)

// The full text of one stage: "#version 450 core", the defines, generated `declarations` (e.g. the
// uniforms of a technique's parameters), then the file with includes expanded.
// Throws GraphicsError if a file or an include is not embedded.
std::string assembleShader(
  const std::string& path, const ShaderDefines& defines = {}, const std::string& declarations = {});

// The raw text of one embedded file (no include expansion), or throws GraphicsError.
const std::string& embeddedShaderText(const std::string& path);

} // namespace sl
