// The interactor style of `shadowlab view`: the viewer's image is a fixed, pixel-exact 2-D view, so no mouse
// drag moves a camera and none of VTK's default keys (w, s, r, 3, e, ...) applies. Typed characters, left clicks
// and window reconfigurations go to the viewer's handlers (cli/ViewerWindow.h), which decide what they do.
// Events replayed by a vtkInteractorEventRecorder arrive here exactly as live ones do.
#pragma once

#include <vtkInteractorStyle.h>

#include <functional>
#include <string>

class vtkSLViewerInteractorStyle : public vtkInteractorStyle
{
public:
  static vtkSLViewerInteractorStyle* New();
  vtkTypeMacro(vtkSLViewerInteractorStyle, vtkInteractorStyle);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // keyCode: the character typed (0 for keys that type none, e.g. Shift); keySym: X's name for the key ("t",
  // "plus", "bracketright", "Escape").
  using KeyHandler = std::function<void(char keyCode, const std::string& keySym)>;
  // Display coordinates of the click: pixels from the window's bottom-left corner.
  using ClickHandler = std::function<void(int x, int y)>;
  using ResizeHandler = std::function<void()>;

  void SetKeyHandler(KeyHandler handler) { this->OnKey = std::move(handler); }
  void SetClickHandler(ClickHandler handler) { this->OnClick = std::move(handler); }
  void SetResizeHandler(ResizeHandler handler) { this->OnResize = std::move(handler); }

  void OnChar() override;
  void OnLeftButtonDown() override;
  void OnConfigure() override;

protected:
  vtkSLViewerInteractorStyle() = default;
  ~vtkSLViewerInteractorStyle() override = default;

private:
  vtkSLViewerInteractorStyle(const vtkSLViewerInteractorStyle&) = delete;
  void operator=(const vtkSLViewerInteractorStyle&) = delete;

  KeyHandler OnKey;
  ClickHandler OnClick;
  ResizeHandler OnResize;
};
