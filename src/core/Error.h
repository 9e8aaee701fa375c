// Errors in ShadowLab come in three kinds:
//  - InputError: something the user gave us (scene file, mesh, CLI, parameter) is wrong. It carries a
//    one-line message naming the file / JSON path / key / value; the CLI catches it once, prints it and
//    exits 1.
//  - GraphicsError: the graphics stack cannot do what we need (no EGL display, GL too old, a shader that
//    does not compile); the CLI prints it as one line and exits 2.
//  - Invariant violations (SL_CHECK): a bug in ShadowLab itself. They abort with expression and location.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace sl
{

class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

// An error from the graphics stack (no EGL display, GL version too old, shader compile failure).
class GraphicsError : public std::runtime_error
{
public:
  explicit GraphicsError(const std::string& message)
    : std::runtime_error(message)
  {
  }
};

// `text` safe to print as one line: control characters (newlines, ANSI escapes, ...), DEL, C1 controls and bytes
// that are not UTF-8 written as \n, \t, \r or \xNN, so a file name or key echoed in a message can neither split
// it nor drive the terminal; well-formed UTF-8 (non-ASCII names) is kept.
std::string printable(const std::string& text);

[[noreturn]] void checkFailed(const char* expression, const char* file, int line, const std::string& message);

// Builds a message from stream-style arguments: format("value ", x, " out of range").
template <typename... Args>
std::string format(const Args&... args)
{
  std::ostringstream stream;
  (stream << ... << args);
  return stream.str();
}

} // namespace sl

#define SL_CHECK(condition)                                                                        \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
      ::sl::checkFailed(#condition, __FILE__, __LINE__, std::string());                            \
  } while (false)

#define SL_CHECK_MSG(condition, ...)                                                               \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
      ::sl::checkFailed(#condition, __FILE__, __LINE__, ::sl::format(__VA_ARGS__));                \
  } while (false)

#ifdef NDEBUG
#define SL_DCHECK(condition)                                                                       \
  do                                                                                               \
  {                                                                                                \
  } while (false)
#else
#define SL_DCHECK(condition) SL_CHECK(condition)
#endif
