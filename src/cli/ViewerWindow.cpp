#include "cli/ViewerWindow.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "io/vtkSLOutputWindow.h"
#include "vis/NumberText.h"
#include "probe/ProbeFigure.h"
#include "vis/Canvas.h"

#include <vtkCamera.h>
#include <vtkImageMapper3D.h>
#include <vtkImageProperty.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <sstream>

namespace sl
{
namespace
{

constexpr int kMarginPx = 8;
constexpr int kStatusFontPx = 13;
constexpr int kStatusLineHeightPx = 16;
// The session's four lines and the last action's, each wrapped to the window's width (issue 31): room for three
// continuation lines; a status longer than that is cut with its last line saying so.
constexpr int kStatusLines = 8;
constexpr int kStatusHeightPx = kStatusLines * kStatusLineHeightPx + 2 * kMarginPx;
// The probe figure (ProbeFigure.h: 1200 wide, 400 a row of panels) shows at full size, two rows of panels at a
// time; f / F scroll it a row (issue 31: fitted into the panel its text was 5 pixels tall).
constexpr int kProbePanelWidthPx = kProbeFigureWidth;
constexpr int kProbePanelHeightPx = 2 * kProbeFigurePanelSide;
constexpr double kBackground[3] = { 0.12, 0.12, 0.12 };


void setImage(vtkImageData* data, const ImageU8& rgb)
{
  SL_CHECK(rgb.components == 3);
  data->SetDimensions(rgb.width, rgb.height, 1);
  data->SetOrigin(0.0, 0.0, 0.0);
  data->SetSpacing(1.0, 1.0, 1.0);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  // Both row 0 at the bottom.
  std::memcpy(data->GetScalarPointer(), rgb.data.data(), rgb.data.size());
  data->Modified();
}

// Points `renderer`'s camera at an image of canvasWidth x canvasHeight pixels (vtkImageData at the origin with
// spacing 1: pixel i spans [i - 0.5, i + 0.5]) so that it shows at `scale` screen pixels per canvas pixel with the
// canvas' bottom-left corner at (left, bottom) viewport pixels. Integer offsets and scale 1 put every canvas pixel
// exactly on one screen pixel.
void placeImage(vtkRenderer* renderer, double scale, double left, double bottom)
{
  const int* size = renderer->GetSize();
  vtkCamera* camera = renderer->GetActiveCamera();
  const double centreX = (0.5 * size[0] - left) / scale - 0.5;
  const double centreY = (0.5 * size[1] - bottom) / scale - 0.5;
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5 * size[1] / scale);
  camera->SetFocalPoint(centreX, centreY, 0.0);
  camera->SetPosition(centreX, centreY, 1.0);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->SetClippingRange(0.5, 1.5);
}

void styleText(vtkTextActor* text, bool centred)
{
  vtkTextProperty* property = text->GetTextProperty();
  property->SetFontFamilyToCourier();
  property->SetFontSize(kStatusFontPx);
  property->SetColor(0.92, 0.92, 0.92);
  property->SetJustification(centred ? VTK_TEXT_CENTERED : VTK_TEXT_LEFT);
  property->SetVerticalJustification(centred ? VTK_TEXT_CENTERED : VTK_TEXT_TOP);
}

// The width of one status character, as VTK's FreeType renders Courier at kStatusFontPx.
int statusCharWidthPx()
{
  static const int width = std::max(1, (measureText("MMMMMMMMMM", kStatusFontPx).width + 9) / 10);
  return width;
}

} // namespace

ViewerWindow::ViewerWindow(ViewerSession& session, void* xDisplay, const std::string& title,
  const std::filesystem::path& screenshotDir, std::ostream& out)
  : session_(session)
  , screenshotDir_(screenshotDir)
  , out_(out)
{
  // The pipeline's context can be made current only while the window's is not (ViewerSession.h).
  session_.setReleaseWindowContext([this] { window_->ReleaseCurrent(); });

  for (const glm::ivec2& size : session_.canvasSizesOfAllBuffers())
  {
    leftPanelWidth_ = std::max(leftPanelWidth_, size.x);
    canvasHeight_ = std::max(canvasHeight_, size.y);
  }
  panelHeight_ = std::max(canvasHeight_, kProbePanelHeightPx);
  const int rightPanelWidth = kProbePanelWidthPx;

  window_->SetDisplayId(xDisplay);
  window_->SetMultiSamples(0);
  window_->SetWindowName(("ShadowLab view: " + printable(title)).c_str());
  window_->SetSize(leftPanelWidth_ + rightPanelWidth + 3 * kMarginPx, kStatusHeightPx + panelHeight_ + kMarginPx);
  // Renderers draw in the order they were added, each clearing its own viewport first.
  for (vtkRenderer* panel : { backdrop_.Get(), imagePanel_.Get(), probePanel_.Get(), statusPanel_.Get() })
  {
    panel->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
    panel->InteractiveOff();
    window_->AddRenderer(panel);
  }
  backdrop_->SetBackground(0.0, 0.0, 0.0); // the margins between the panels

  for (vtkImageActor* actor : { imageActor_.Get(), probeActor_.Get() })
  {
    // Draw the edge pixels whole (VTK draws half of them by default).
    actor->GetMapper()->BorderOn();
    actor->GetProperty()->SetInterpolationTypeToNearest();
  }
  imageActor_->GetMapper()->SetInputData(imageData_);
  probeActor_->GetMapper()->SetInputData(probeData_);
  imagePanel_->AddActor(imageActor_);
  probePanel_->AddActor(probeActor_);

  styleText(statusText_, false);
  styleText(probeHint_, true);
  styleText(keysText_, false);
  // The keys over the probe panel, on an opaque backing so they read over the figure (h shows and hides them).
  keysText_->GetTextProperty()->SetBackgroundColor(0.0, 0.0, 0.0);
  keysText_->GetTextProperty()->SetBackgroundOpacity(0.9);
  keysText_->GetTextProperty()->SetFrame(1);
  keysText_->GetTextProperty()->SetFrameColor(0.92, 0.92, 0.92);
  keysText_->SetInput(keyHelp().c_str());
  keysText_->VisibilityOff();
  statusPanel_->AddActor2D(statusText_);
  probePanel_->AddActor2D(probeHint_);
  probePanel_->AddActor2D(keysText_);

  style_->KeyPressActivationOff();
  style_->SetKeyHandler([this](char keyCode, const std::string& keySym) { handleKey(keyCode, keySym); });
  style_->SetClickHandler([this](int x, int y) { handleClick(x, y); });
  style_->SetResizeHandler([this] {
    layout();
    refresh();
  });
  interactor_->SetRenderWindow(window_);
  interactor_->SetInteractorStyle(style_);
}

ViewerWindow::~ViewerWindow()
{
  if (recorder_)
  {
    recorder_->Stop();
    recorder_->Off();
    recorder_->SetInteractor(nullptr);
  }
  if (player_)
  {
    player_->SetInteractor(nullptr);
  }
  // The window's GL objects go with its context, before the pipeline's are freed (ViewerSession.h).
  window_->Finalize();
  session_.setReleaseWindowContext(nullptr);
}

std::string ViewerWindow::keyHelp()
{
  return "t / T       next / previous technique (registry order)\n"
         "b / B       next / previous buffer: image, visibility, the technique's buffers as heat maps\n"
         "p / P       select the technique's next / previous parameter\n"
         "+ / -       step the selected parameter up / down within its range (= and _ too)\n"
         "] / [       light size times / divided by 1.25 (area lights)\n"
         "r           reset the technique's parameters and the light size\n"
         "left click  probe that pixel: its probe figure beside the image, the pixel ringed\n"
         "f / F       scroll the probe figure down / up a row of panels\n"
         "c           clear the probe\n"
         "s           save a screenshot (PNG) into --screenshot-dir\n"
         "h           print these keys (and show / hide them in the window)\n"
         "q, Escape   quit\n";
}

void ViewerWindow::show()
{
  interactor_->Initialize();
  layout();
  refresh();
  // Where the image lies, for whoever scripts clicks (tests/data/view/record_session.sh).
  const int* size = window_->GetSize();
  const int* origin = imagePanel_->GetOrigin();
  const int zoom = session_.canvas().zoom;
  const glm::ivec2 offset = imageOffset();
  report(format("window ", size[0], "x", size[1], ": image pixel (x, y) at window pixel (", origin[0] + offset.x, " + ",
    zoom, "x, ", origin[1] + offset.y, " + ", zoom, "y) from the bottom-left corner"));
  report("showing " + session_.technique() + ", " + session_.buffer() + " (h: keys)");
}

void ViewerWindow::record(const std::string& file)
{
  recorder_ = vtkSmartPointer<vtkInteractorEventRecorder>::New();
  recorder_->KeyPressActivationOff(); // by default the i key would switch the recorder on and off
  recorder_->SetInteractor(interactor_);
  recorder_->SetFileName(file.c_str());
  VtkErrorCapture capture;
  recorder_->On();
  recorder_->Record();
  if (capture.hasError())
  {
    throw InputError("--record " + printable(file) + ": " + capture.firstError());
  }
}

void ViewerWindow::play(const std::string& file)
{
  player_ = vtkSmartPointer<vtkInteractorEventRecorder>::New();
  player_->KeyPressActivationOff();
  player_->SetInteractor(interactor_);
  player_->SetFileName(file.c_str());
  VtkErrorCapture capture;
  player_->Play();
  if (capture.hasError())
  {
    throw InputError("--play " + printable(file) + ": " + capture.firstError());
  }
}

void ViewerWindow::run()
{
  if (!quit_)
  {
    interactor_->Start();
  }
}

void ViewerWindow::report(const std::string& line)
{
  out_ << "view: " << line << std::endl;
  lastAction_ = line;
}

void ViewerWindow::handleKey(char keyCode, const std::string& keySym)
{
  if (quit_ || keyCode == 0)
  {
    return; // after q; keys that type nothing (Shift, Control)
  }
  try
  {
    switch (keyCode)
    {
      case 't': report(session_.cycleTechnique(1)); break;
      case 'T': report(session_.cycleTechnique(-1)); break;
      case 'b': report(session_.cycleBuffer(1)); break;
      case 'B': report(session_.cycleBuffer(-1)); break;
      case 'p': report(session_.selectParameter(1)); break;
      case 'P': report(session_.selectParameter(-1)); break;
      case '+':
      case '=': report(session_.stepParameter(1)); break;
      case '-':
      case '_': report(session_.stepParameter(-1)); break;
      case ']': report(session_.stepLightSize(1)); break;
      case '[': report(session_.stepLightSize(-1)); break;
      case 'r': report(session_.resetParameters()); break;
      case 'c':
        report(session_.clearProbe());
        figureScrollRows_ = 0;
        break;
      case 'f': report(scrollFigure(1)); break;
      case 'F': report(scrollFigure(-1)); break;
      case 's': saveScreenshot(); break;
      case 'h':
        out_ << keyHelp() << std::flush;
        keysText_->SetVisibility(!keysText_->GetVisibility());
        report(keysText_->GetVisibility() ? "keys shown in the window (h hides them) and printed on the terminal"
                                          : "keys hidden (h shows them)");
        break;
      case 'q':
      case 27: // Escape
        quit_ = true;
        report("quit");
        interactor_->TerminateApp();
        return;
      default:
        report("key '" + printable(keySym.empty() ? std::string(1, keyCode) : keySym) + "' does nothing (h: keys)");
    }
  }
  catch (const InputError& error)
  {
    // The session is as it was before the key (ViewerSession): say why and go on.
    report(std::string("refused: ") + printable(error.what()));
  }
  refresh();
}

void ViewerWindow::handleClick(int x, int y)
{
  if (quit_)
  {
    return;
  }
  const int* origin = imagePanel_->GetOrigin();
  const int* size = imagePanel_->GetSize();
  if (x < origin[0] || y < origin[1] || x >= origin[0] + size[0] || y >= origin[1] + size[1])
  {
    return; // outside the image panel: nothing to probe there
  }
  imagePanel_->SetDisplayPoint(x + 0.5, y + 0.5, 0.0); // the centre of the clicked screen pixel
  imagePanel_->DisplayToWorld();
  const double* world = imagePanel_->GetWorldPoint();
  const glm::ivec2 canvasPixel(
    static_cast<int>(std::floor(world[0] / world[3] + 0.5)), static_cast<int>(std::floor(world[1] / world[3] + 0.5)));
  const std::optional<glm::ivec2> pixel = session_.imagePixelAt(canvasPixel);
  if (!pixel)
  {
    report("the click is not on the image: nothing probed");
  }
  else
  {
    try
    {
      report(session_.probeAt(*pixel));
    }
    catch (const InputError& error)
    {
      report(std::string("refused: ") + printable(error.what()));
    }
  }
  refresh();
}

void ViewerWindow::layout()
{
  const int* size = window_->GetSize();
  const double width = std::max(size[0], 1);
  const double height = std::max(size[1], 1);
  const int panelBottom = kStatusHeightPx;
  const int panelTop = std::max(panelBottom + 1, size[1] - kMarginPx);
  const int leftEnd = std::min(kMarginPx + leftPanelWidth_, std::max(size[0] - 2 * kMarginPx, kMarginPx + 1));
  const int rightStart = std::min(leftEnd + kMarginPx, size[0] - 1);
  const int rightEnd = std::max(rightStart + 1, size[0] - kMarginPx);
  // Fractions of whole pixels: VTK rounds them back to exactly these pixels.
  imagePanel_->SetViewport(kMarginPx / width, panelBottom / height, leftEnd / width, panelTop / height);
  probePanel_->SetViewport(rightStart / width, panelBottom / height, rightEnd / width, panelTop / height);
  statusPanel_->SetViewport(0.0, 0.0, 1.0, panelBottom / height);
  statusText_->SetPosition(kMarginPx, kStatusHeightPx - kMarginPx);
  probeHint_->SetPosition(0.5 * (rightEnd - rightStart), 0.5 * (panelTop - panelBottom));
  keysText_->SetPosition(kMarginPx, panelTop - panelBottom - kMarginPx);
}

glm::ivec2 ViewerWindow::imageOffset() const
{
  // Centred on the largest canvas of the buffers, so an image pixel stays put whatever buffer is on show.
  const int* size = imagePanel_->GetSize();
  return { std::max(0, (size[0] - leftPanelWidth_) / 2), std::max(0, (size[1] - canvasHeight_) / 2) };
}

std::string ViewerWindow::scrollFigure(int rows)
{
  const ImageU8* figure = session_.probeFigureImage();
  if (figure == nullptr)
  {
    return "no probe figure to scroll (click a pixel)";
  }
  const int* probeSize = probePanel_->GetSize();
  const int rowCount = figure->height / kProbeFigurePanelSide;
  const int shownRows = std::max(1, probeSize[1] / kProbeFigurePanelSide);
  const int lastFirstRow = std::max(0, rowCount - shownRows);
  figureScrollRows_ = std::clamp(figureScrollRows_ + rows, 0, lastFirstRow);
  return format("probe figure rows ", figureScrollRows_ + 1, "..", std::min(rowCount, figureScrollRows_ + shownRows),
    " of ", rowCount);
}

void ViewerWindow::refresh()
{
  // Left: the canvas 1:1 from the panel's bottom-left corner, smaller only when the window is too small for it.
  const ViewerCanvas& canvas = session_.canvas();
  setImage(imageData_, canvas.rgb);
  const int* imageSize = imagePanel_->GetSize();
  const double fitLeft = std::min({ 1.0, static_cast<double>(imageSize[0]) / canvas.rgb.width,
    static_cast<double>(imageSize[1]) / canvas.rgb.height });
  const glm::ivec2 offset = fitLeft < 1.0 ? glm::ivec2(0) : imageOffset();
  placeImage(imagePanel_, fitLeft, offset.x, offset.y);
  imageActor_->GetProperty()->SetInterpolationType(
    fitLeft < 1.0 ? VTK_LINEAR_INTERPOLATION : VTK_NEAREST_INTERPOLATION);

  // Right: the probe figure at full size, its top (or the row f scrolled to) at the panel's top, centred
  // across; shrunk (smoothly) only when the window is narrower than the figure.
  if (const ImageU8* figure = session_.probeFigureImage())
  {
    setImage(probeData_, *figure);
    const int* probeSize = probePanel_->GetSize();
    const int rowCount = figure->height / kProbeFigurePanelSide;
    figureScrollRows_ = std::clamp(figureScrollRows_, 0, std::max(0, rowCount - 1));
    const double fit = std::min(1.0, static_cast<double>(probeSize[0]) / figure->width);
    const double shownTop = figure->height - figureScrollRows_ * kProbeFigurePanelSide; // figure rows above: scrolled off
    const double bottom = fit * figure->height <= probeSize[1] ? std::floor(0.5 * (probeSize[1] - fit * figure->height))
                                                               : std::floor(probeSize[1] - fit * shownTop);
    placeImage(probePanel_, fit, std::floor(0.5 * (probeSize[0] - fit * figure->width)), bottom);
    probeActor_->GetProperty()->SetInterpolationType(fit < 1.0 ? VTK_LINEAR_INTERPOLATION : VTK_NEAREST_INTERPOLATION);
    probeActor_->VisibilityOn();
    probeHint_->VisibilityOff();
  }
  else
  {
    probeActor_->VisibilityOff();
    probeHint_->SetInput("click a pixel of the image to probe it");
    probeHint_->VisibilityOn();
  }

  // The status wrapped to the window's width (Courier: one width for every character).
  const int* windowSize = window_->GetSize();
  const std::size_t maxChars = static_cast<std::size_t>(
    std::max(16, (windowSize[0] - 2 * kMarginPx) / std::max(1, statusCharWidthPx())));
  std::vector<std::string> lines = session_.statusLines();
  if (lastAction_ != lines.back())
  {
    lines.push_back(lastAction_); // the probe line already says what a click did
  }
  std::vector<std::string> wrapped;
  for (const std::string& line : lines)
  {
    for (const std::string& part : wrapAtSpaces(line, maxChars))
    {
      wrapped.push_back(part);
    }
  }
  if (wrapped.size() > std::size_t(kStatusLines))
  {
    wrapped.resize(std::size_t(kStatusLines));
    wrapped.back() = "  (more on the terminal)";
  }
  std::string status;
  for (const std::string& line : wrapped)
  {
    status += line + "\n";
  }
  statusText_->SetInput(status.c_str());
  window_->Render();
}

void ViewerWindow::saveScreenshot()
{
  std::error_code error;
  std::filesystem::create_directories(screenshotDir_, error);
  if (error || !std::filesystem::is_directory(screenshotDir_))
  {
    throw InputError("--screenshot-dir " + printable(screenshotDir_.string()) + ": cannot create the directory" +
      (error ? " (" + error.message() + ")" : std::string()));
  }
  // Numbered after the highest view-NNN-* already there: a screenshot never replaces a file, and the numbers say
  // in which order they were taken.
  int number = 0;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(screenshotDir_, error))
  {
    const std::string name = entry.path().filename().string();
    const std::size_t digitsEnd = name.find_first_not_of("0123456789", 5);
    if (name.compare(0, 5, "view-") == 0 && digitsEnd != std::string::npos && digitsEnd > 5 && digitsEnd < 14 &&
      name[digitsEnd] == '-')
    {
      number = std::max(number, std::stoi(name.substr(5, digitsEnd - 5)));
    }
  }
  std::ostringstream name;
  name << "view-" << std::setw(3) << std::setfill('0') << number + 1 << "-" << session_.technique() << "-"
       << session_.buffer() << ".png";
  const std::filesystem::path path = screenshotDir_ / name.str();
  refresh(); // what the screenshot shows is what the status says
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window_);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOn();
  grab->Update();
  vtkImageData* pixels = grab->GetOutput();
  int dimensions[3] = { 0, 0, 0 };
  pixels->GetDimensions(dimensions);
  ImageU8 rgb(dimensions[0], dimensions[1], 3);
  std::memcpy(rgb.data.data(), pixels->GetScalarPointer(), rgb.data.size()); // both row 0 at the bottom
  writePng(path, rgb);
  report("screenshot " + printable(path.string()) + " = " + session_.renderCommand());
}

} // namespace sl
