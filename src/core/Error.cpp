#include "core/Error.h"

#include <cstdio>
#include <cstdlib>

namespace sl
{

std::string printable(const std::string& text)
{
  std::string shown;
  shown.reserve(text.size());
  for (const char c : text)
  {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n')
      shown += "\\n";
    else if (c == '\r')
      shown += "\\r";
    else if (c == '\t')
      shown += "\\t";
    else if (byte < 0x20 || byte == 0x7f)
    {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
      shown += escaped;
    }
    else
      shown += c;
  }
  return shown;
}

void checkFailed(const char* expression, const char* file, int line, const std::string& message)
{
  std::fprintf(stderr, "shadowlab: internal check failed: %s at %s:%d%s%s\n", expression, file, line,
    message.empty() ? "" : ": ", message.c_str());
  std::abort();
}

} // namespace sl
