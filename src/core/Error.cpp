#include "core/Error.h"

#include <cstdio>
#include <cstdlib>

namespace sl
{

namespace
{

// Length of the well-formed UTF-8 sequence starting at text[at] (RFC 3629: no overlongs, no surrogates, at most
// U+10FFFF), or 0 when it is not one.
std::size_t utf8SequenceLength(const std::string& text, std::size_t at)
{
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  std::size_t length = 0;
  unsigned char secondMin = 0x80;
  unsigned char secondMax = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF)
    length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF)
  {
    length = 3;
    secondMin = lead == 0xE0 ? 0xA0 : 0x80;
    secondMax = lead == 0xED ? 0x9F : 0xBF;
  }
  else if (lead >= 0xF0 && lead <= 0xF4)
  {
    length = 4;
    secondMin = lead == 0xF0 ? 0x90 : 0x80;
    secondMax = lead == 0xF4 ? 0x8F : 0xBF;
  }
  if (length == 0 || at + length > text.size() || byte(at + 1) < secondMin || byte(at + 1) > secondMax)
    return 0;
  for (std::size_t i = 2; i < length; ++i)
    if (byte(at + i) < 0x80 || byte(at + i) > 0xBF)
      return 0;
  return length;
}

void appendEscaped(std::string& shown, unsigned char byte)
{
  char escaped[8];
  std::snprintf(escaped, sizeof(escaped), "\\x%02x", byte);
  shown += escaped;
}

} // namespace

std::string printable(const std::string& text)
{
  std::string shown;
  shown.reserve(text.size());
  for (std::size_t at = 0; at < text.size();)
  {
    const char c = text[at];
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x80)
    {
      // Well-formed UTF-8 (a non-ASCII file name) passes; a C1 control (U+0080..U+009F: 0xC2 0x80..0x9F, which
      // some terminals obey as escapes) and bytes that are not UTF-8 are escaped.
      const std::size_t length = utf8SequenceLength(text, at);
      const bool c1Control = length == 2 && byte == 0xC2 && static_cast<unsigned char>(text[at + 1]) <= 0x9F;
      if (length == 0 || c1Control)
      {
        appendEscaped(shown, byte);
        ++at;
      }
      else
      {
        shown.append(text, at, length);
        at += length;
      }
      continue;
    }
    if (c == '\n')
      shown += "\\n";
    else if (c == '\r')
      shown += "\\r";
    else if (c == '\t')
      shown += "\\t";
    else if (byte < 0x20 || byte == 0x7f)
      appendEscaped(shown, byte);
    else
      shown += c;
    ++at;
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
