#include "io/vtkSLOutputWindow.h"

#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <regex>

vtkStandardNewMacro(vtkSLOutputWindow);

namespace
{

// Captures alive on this thread, innermost last. Thread-local because VTK reports on the thread that hit
// the problem, and a capture must only see what its own operation reported.
thread_local std::vector<sl::VtkErrorCapture*> capturesOfThisThread;

std::mutex installMutex;
std::mutex printMutex;
bool fullMessages = false; // SHADOWLAB_VTK_LOG=full

const char* kindName(sl::VtkErrorCapture::Kind kind)
{
  switch (kind)
  {
  case sl::VtkErrorCapture::Kind::Error:
    return "VTK error";
  case sl::VtkErrorCapture::Kind::Warning:
    return "VTK warning";
  default:
    return "VTK";
  }
}

// Drops ANSI escape sequences (ESC [ ... final byte) and every other control character except line breaks;
// '\r' becomes a line break.
std::string withoutControlCharacters(const std::string& text)
{
  std::string clean;
  clean.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0x1b)
    {
      if (i + 1 < text.size() && text[i + 1] == '[')
      {
        i += 2;
        while (i < text.size() && !(text[i] >= 0x40 && text[i] <= 0x7e))
          ++i;
      }
      continue;
    }
    if (c == '\r' || c == '\n')
      clean.push_back('\n');
    else if (c == '\t')
      clean.push_back(' ');
    else if (c >= 0x20 && c != 0x7f)
      clean.push_back(static_cast<char>(c));
  }
  return clean;
}

std::string trimmed(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(' ');
  if (first == std::string::npos)
    return {};
  const std::size_t last = text.find_last_not_of(' ');
  return text.substr(first, last - first + 1);
}

} // namespace

void vtkSLOutputWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PrintUncaptured: " << (this->PrintUncaptured ? "On" : "Off") << "\n";
  os << indent << "UncapturedMessageCount: " << this->UncapturedMessageCount << "\n";
}

void vtkSLOutputWindow::DisplayText(const char* text)
{
  const std::string message = text ? text : "";
  sl::VtkErrorCapture::Kind kind = sl::VtkErrorCapture::Kind::Text;
  switch (this->GetCurrentMessageType())
  {
  case MESSAGE_TYPE_ERROR:
    kind = sl::VtkErrorCapture::Kind::Error;
    break;
  case MESSAGE_TYPE_WARNING:
  case MESSAGE_TYPE_GENERIC_WARNING:
    kind = sl::VtkErrorCapture::Kind::Warning;
    break;
  default: // plain text and debug output
    break;
  }
  if (!capturesOfThisThread.empty())
  {
    capturesOfThisThread.back()->record(kind, message);
  }
  else
  {
    const std::lock_guard<std::mutex> lock(printMutex);
    ++this->UncapturedMessageCount;
    const std::string line = sl::vtkMessageLine(message);
    if (this->PrintUncaptured && !line.empty())
      std::cerr << "shadowlab: " << kindName(kind) << ": " << (fullMessages ? message : line) << std::endl;
  }
  // Observers of the window (none in ShadowLab) still see every message, as with vtkOutputWindow.
  this->InvokeEvent(vtkCommand::MessageEvent, const_cast<char*>(message.c_str()));
}

namespace sl
{

void installVtkOutputWindow()
{
  const std::lock_guard<std::mutex> lock(installMutex);
  // vtkLogger prints VTK's own "ERR|" blocks (multi-line, coloured) before the output window is asked;
  // with stderr off, the window below is the only way VTK's text can reach the user.
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  if (vtkSLOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance()) != nullptr)
    return;
  vtkNew<vtkSLOutputWindow> window;
  const char* logFlag = std::getenv("SHADOWLAB_VTK_LOG");
  // SHADOWLAB_VTK_LOG=1 prints each uncaptured message's first line; =full prints it whole (a GLSL compiler log).
  fullMessages = logFlag != nullptr && std::strcmp(logFlag, "full") == 0;
  window->SetPrintUncaptured(logFlag != nullptr && (std::strcmp(logFlag, "1") == 0 || fullMessages));
  vtkOutputWindow::SetInstance(window);
}

std::string vtkMessageLine(const std::string& text)
{
  // vtkOutputWindowDisplayErrorText() formats "ERROR: In <file>, line <n>\n<class> (0x...): <message>\n\n";
  // the header names VTK's source file, which tells a user nothing about theirs.
  static const std::regex header(R"(^(ERROR|Warning|Generic Warning|Debug): In .*, line \d+$)");
  static const std::regex objectPrefix(R"(^vtk\w+ \((0x[0-9a-fA-F]+|nil)\): )");
  static const std::regex address(R"( \((0x[0-9a-fA-F]+|nil)\))");

  const std::string clean = withoutControlCharacters(text);
  std::size_t start = 0;
  while (start <= clean.size())
  {
    std::size_t end = clean.find('\n', start);
    if (end == std::string::npos)
      end = clean.size();
    const std::string line = trimmed(clean.substr(start, end - start));
    start = end + 1;
    if (line.empty() || std::regex_match(line, header))
      continue;
    // Object addresses differ from run to run and mean nothing to a user.
    return trimmed(std::regex_replace(std::regex_replace(line, objectPrefix, ""), address, ""));
  }
  return {};
}

VtkErrorCapture::VtkErrorCapture()
{
  installVtkOutputWindow();
  capturesOfThisThread.push_back(this);
}

VtkErrorCapture::~VtkErrorCapture()
{
  // Captures are scoped, so this one is the innermost; search anyway so a misuse cannot leave a dangling one.
  const auto self = std::find(capturesOfThisThread.rbegin(), capturesOfThisThread.rend(), this);
  if (self != capturesOfThisThread.rend())
    capturesOfThisThread.erase(std::next(self).base());
}

bool VtkErrorCapture::hasError() const
{
  return std::any_of(
    messages_.begin(), messages_.end(), [](const Message& message) { return message.kind == Kind::Error; });
}

std::string VtkErrorCapture::firstError() const
{
  bool sawError = false;
  for (const Message& message : messages_)
  {
    if (message.kind != Kind::Error)
      continue;
    sawError = true;
    if (!message.line.empty())
      return message.line;
  }
  return sawError ? "VTK reported an error without text" : "";
}

void VtkErrorCapture::record(Kind kind, const std::string& text)
{
  messages_.push_back({ kind, vtkMessageLine(text) });
}

} // namespace sl
