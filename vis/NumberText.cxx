#include "vis/NumberText.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sl
{

std::string readableNumber(double value, int significant)
{
  if (!std::isfinite(value))
  {
    return std::isnan(value) ? "n/a" : (value > 0.0 ? "inf" : "-inf");
  }
  significant = std::max(1, significant);
  char text[64];
  const double magnitude = std::abs(value);
  if (magnitude >= std::pow(10.0, significant) && magnitude < 1e6)
  {
    // Whole units are what a person reads for a count or a large size; %g would write 1.23e+03.
    std::snprintf(text, sizeof(text), "%.0f", value);
  }
  else
  {
    std::snprintf(text, sizeof(text), "%.*g", significant, value);
  }
  std::string result = text;
  if (result == "-0")
  {
    result = "0";
  }
  return result;
}

std::vector<std::string> distinctTickLabels(const std::vector<double>& values, int minSignificant)
{
  std::vector<std::string> labels;
  for (int significant = std::max(1, minSignificant); significant <= 15; ++significant)
  {
    labels.clear();
    for (const double value : values)
    {
      labels.push_back(readableNumber(value, significant));
    }
    bool distinct = true;
    for (std::size_t i = 0; i < values.size() && distinct; ++i)
    {
      for (std::size_t j = i + 1; j < values.size() && distinct; ++j)
      {
        distinct = values[i] == values[j] || labels[i] != labels[j];
      }
    }
    if (distinct)
    {
      break;
    }
  }
  return labels;
}

std::vector<std::string> wrapAtSpaces(const std::string& text, std::size_t maxChars)
{
  std::vector<std::string> lines;
  std::string rest = text;
  maxChars = std::max<std::size_t>(maxChars, 16);
  while (rest.size() > maxChars)
  {
    std::size_t cut = rest.rfind(' ', maxChars);
    if (cut == std::string::npos || cut < maxChars / 2)
    {
      cut = maxChars;
    }
    lines.push_back(rest.substr(0, cut));
    rest = "  " + rest.substr(rest[cut] == ' ' ? cut + 1 : cut);
  }
  lines.push_back(rest);
  return lines;
}

} // namespace sl
