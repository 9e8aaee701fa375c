// Parsing of user-given text shared by the CLI and the technique registry.
#pragma once

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace sl
{

// The whole of `text` as a finite decimal number, or nullopt ("", "1x", " 1", "nan", "inf" and hexadecimal
// "0x10" are not numbers: strtod would take the last three).
inline std::optional<double> parseNumber(const std::string& text)
{
  if (text.find_first_not_of("0123456789+-.eE") != std::string::npos)
  {
    return std::nullopt;
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  const bool whole = !text.empty() && end == text.c_str() + text.size();
  return whole && std::isfinite(value) ? std::optional<double>(value) : std::nullopt;
}

} // namespace sl
