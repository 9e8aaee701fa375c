// What the bench charts share: an offscreen vtkChartXY on an EGL window (white background, title, legend),
// a logarithmic axis drawn as log10 values with decade ticks (VTK 9.1's vtkAxis::SetLogScale draws no plots
// offscreen here), and writing the window to PNG.
#pragma once

#include <vtkChartXY.h>
#include <vtkContextView.h>
#include <vtkSmartPointer.h>

#include <filesystem>
#include <string>

class vtkAxis;
class vtkSLEglRenderWindow;

namespace sl
{

struct OffscreenChart
{
  vtkSmartPointer<vtkSLEglRenderWindow> window;
  vtkSmartPointer<vtkContextView> view;
  vtkSmartPointer<vtkChartXY> chart;
};
OffscreenChart makeOffscreenChart(const std::string& title, int width = 960, int height = 640);

// Fixes `axis` to [logMin, logMax] (log10 units) with ticks at 1, 2, 5 x 10^k (every integer mantissa over
// a narrow range), labelled in the original units.
void setLogAxis(vtkAxis* axis, double logMin, double logMax, const std::string& title);

// Renders the chart and writes it; throws InputError when the PNG cannot be written.
void writeChartPng(const OffscreenChart& chart, const std::filesystem::path& pngPath);

} // namespace sl
