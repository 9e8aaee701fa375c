// Parsing of user-given text shared by the CLI and the technique registry.
#pragma once

#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

namespace sl
{

// The whole of `text` as a finite number, or nullopt ("", "1x", "nan" and "inf" are not numbers).
inline std::optional<double> parseNumber(const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  const bool whole = !text.empty() && end == text.c_str() + text.size();
  return whole && std::isfinite(value) ? std::optional<double>(value) : std::nullopt;
}

} // namespace sl
