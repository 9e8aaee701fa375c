// The window of `shadowlab view`: VTK's own render window and interactor (vtkXOpenGLRenderWindow on Debian's
// VTK 9.1) showing what a ViewerSession holds, as images:
//
//   +----------------------------+--------------------------------------+
//   | the buffer on show (image, | the probe figure of the clicked      |
//   | visibility or a heat map   | pixel (probeFigure) at full size,    |
//   | with its colour key), the  | two rows of its panels at a time     |
//   | probed pixel ringed        | (f / F scroll); h: the keys over it  |
//   +----------------------------+--------------------------------------+
//   | status: technique, buffer, selected parameter and light size, probe, |
//   | the last action; wrapped to the window's width                      |
//   +--------------------------------------------------------------------+
//
// The left panel shows its canvas 1:1 (the session already enlarged small frames), centred on the largest canvas
// of the buffers, so an image pixel stays at the same place on the screen whatever buffer is on show. Keys and
// clicks go through vtkSLViewerInteractorStyle; every action prints one line on `out`.
#pragma once

#include "cli/ViewerSession.h"
#include "cli/vtkSLViewerInteractorStyle.h"

#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>

#include <glm/glm.hpp>

#include <filesystem>
#include <ostream>
#include <string>

namespace sl
{

class ViewerWindow
{
public:
  // `xDisplay`: an open Display* (XDisplay::handle()) that outlives the window.
  ViewerWindow(ViewerSession& session, void* xDisplay, const std::string& title,
    const std::filesystem::path& screenshotDir, std::ostream& out);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  // Maps the window and shows the first frame.
  void show();
  // Writes every event of the session to `file` from now on (vtkInteractorEventRecorder; VTK's recorder stops
  // at the q that ends the session and does not write it).
  void record(const std::string& file);
  // Replays the events in `file` (as record() wrote them) and returns at its end, or at a q in it.
  void play(const std::string& file);
  // The interactive event loop, until q or the window is closed.
  void run();
  bool quitRequested() const { return quit_; }

  // The keys, one per line (h prints them; docs/tools.md, "The viewer").
  static std::string keyHelp();

private:
  void handleKey(char keyCode, const std::string& keySym);
  void handleClick(int x, int y);
  void layout();  // viewports and cameras for the window's current size
  void refresh(); // the session's canvas, probe figure and status into the actors, then Render()
  void saveScreenshot();
  glm::ivec2 imageOffset() const;    // where the canvas' bottom-left corner sits in the image panel
  std::string scrollFigure(int rows); // f / F
  void report(const std::string& line);

  ViewerSession& session_;
  std::filesystem::path screenshotDir_;
  std::ostream& out_;
  bool quit_ = false;
  std::string lastAction_; // the status' last line
  int leftPanelWidth_ = 0;  // the widest canvas of the first frame's buffers
  int canvasHeight_ = 0;    // the tallest canvas of the first frame's buffers
  int panelHeight_ = 0;     // at least two rows of the probe figure's panels
  int figureScrollRows_ = 0; // probe-figure rows scrolled off the panel's top

  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderer> backdrop_; // the whole window, under the panels: no pixel is left undrawn
  vtkNew<vtkRenderer> imagePanel_;
  vtkNew<vtkRenderer> probePanel_;
  vtkNew<vtkRenderer> statusPanel_;
  vtkNew<vtkImageData> imageData_;
  vtkNew<vtkImageData> probeData_;
  vtkNew<vtkImageActor> imageActor_;
  vtkNew<vtkImageActor> probeActor_;
  vtkNew<vtkTextActor> statusText_;
  vtkNew<vtkTextActor> probeHint_;
  vtkNew<vtkTextActor> keysText_; // h: the keys over the probe panel
  vtkNew<vtkSLViewerInteractorStyle> style_;
  vtkNew<vtkRenderWindowInteractor> interactor_;
  // Declared after the interactor they observe, so that they go first.
  vtkSmartPointer<vtkInteractorEventRecorder> recorder_;
  vtkSmartPointer<vtkInteractorEventRecorder> player_;
};

} // namespace sl
