// VTK's error and warning text, routed into ShadowLab's error path instead of the terminal.
//
// By default VTK 9.1 reports a vtkErrorMacro twice over: vtkLogger prints a multi-line, ANSI-coloured
// "ERR|" block on stderr, and the vtkOutputWindow singleton may print the raw text as well. Neither is
// the one-line "shadowlab: error: ..." the CLI promises. installVtkOutputWindow() replaces the singleton
// with a vtkSLOutputWindow and turns vtkLogger's stderr output off, so nothing from VTK reaches stderr on
// its own. Every message then goes to the innermost sl::VtkErrorCapture alive on the reporting thread;
// a reader that starts a capture around Update() folds the first captured error into its InputError:
//
//   sl::VtkErrorCapture capture;
//   reader->Update();
//   if (capture.hasError())
//     throw InputError(file + ": not a readable VTK image file (" + capture.firstError() + ")");
//
// A message that no capture took is counted and, when SHADOWLAB_VTK_LOG=1 is set in the environment,
// printed on stderr as one line ("shadowlab: VTK error: ..."), so it is never lost without a way to see it.
#pragma once

#include <vtkOutputWindow.h>

#include <string>
#include <vector>

class vtkSLOutputWindow : public vtkOutputWindow
{
public:
  static vtkSLOutputWindow* New();
  vtkTypeMacro(vtkSLOutputWindow, vtkOutputWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // Every Display*Text of vtkOutputWindow ends here, with CurrentMessageType telling which kind it is.
  void DisplayText(const char* text) override;

  // Print messages no capture took on stderr, one line each (installVtkOutputWindow sets it from
  // SHADOWLAB_VTK_LOG=1).
  vtkSetMacro(PrintUncaptured, bool);
  vtkGetMacro(PrintUncaptured, bool);
  vtkBooleanMacro(PrintUncaptured, bool);

  // Messages that arrived while no capture was alive on their thread, since this window was created.
  vtkGetMacro(UncapturedMessageCount, vtkIdType);

protected:
  vtkSLOutputWindow() = default;
  ~vtkSLOutputWindow() override = default;

private:
  vtkSLOutputWindow(const vtkSLOutputWindow&) = delete;
  void operator=(const vtkSLOutputWindow&) = delete;

  bool PrintUncaptured = false;
  vtkIdType UncapturedMessageCount = 0;
};

namespace sl
{

// Makes a vtkSLOutputWindow VTK's output window and silences vtkLogger on stderr. Idempotent; main()
// calls it first thing, and every VtkErrorCapture calls it too, so library users (tests) are covered.
void installVtkOutputWindow();

// One VTK message reduced to one line: VTK's "ERROR: In <source file>, line <n>" header and the
// "<vtkClass> (0x...): " prefix removed, colour codes and control characters dropped, only the first line
// of the text kept, trimmed. "" when nothing is left.
std::string vtkMessageLine(const std::string& text);

// Collects the VTK messages reported on this thread while it is alive (RAII). Captures nest; the
// innermost one receives the messages. Not copyable or movable: the window holds its address.
class VtkErrorCapture
{
public:
  enum class Kind
  {
    Error,
    Warning,
    Text
  };
  struct Message
  {
    Kind kind;
    std::string line; // vtkMessageLine of the text
  };

  VtkErrorCapture();
  ~VtkErrorCapture();
  VtkErrorCapture(const VtkErrorCapture&) = delete;
  VtkErrorCapture& operator=(const VtkErrorCapture&) = delete;

  bool hasError() const;
  // The first error's line ("" when there was none).
  std::string firstError() const;
  const std::vector<Message>& messages() const { return messages_; }

  // Called by vtkSLOutputWindow.
  void record(Kind kind, const std::string& text);

private:
  std::vector<Message> messages_;
};

} // namespace sl
