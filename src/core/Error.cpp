#include "core/Error.h"

#include <cstdio>
#include <cstdlib>

namespace sl
{

void checkFailed(const char* expression, const char* file, int line, const std::string& message)
{
  std::fprintf(stderr, "shadowlab: internal check failed: %s at %s:%d%s%s\n", expression, file, line,
    message.empty() ? "" : ": ", message.c_str());
  std::abort();
}

} // namespace sl
