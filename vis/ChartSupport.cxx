#include "vis/ChartSupport.h"

#include "core/Error.h"
#include "gl/vtkSLEglRenderWindow.h"
#include "io/ImageIO.h"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkContextScene.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

namespace sl
{

OffscreenChart makeOffscreenChart(const std::string& title, int width, int height)
{
  OffscreenChart result;
  result.window = vtkSmartPointer<vtkSLEglRenderWindow>::New();
  result.window->InitializeOffscreen(width, height);
  result.view = vtkSmartPointer<vtkContextView>::New();
  result.view->SetRenderWindow(result.window);
  result.view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  result.chart = vtkSmartPointer<vtkChartXY>::New();
  result.view->GetScene()->AddItem(result.chart);
  result.chart->SetTitle(title);
  result.chart->GetTitleProperties()->SetFontSize(16);
  result.chart->SetShowLegend(true);
  result.chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  result.chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  return result;
}

void setLogAxis(vtkAxis* axis, double logMin, double logMax, const std::string& title)
{
  vtkNew<vtkDoubleArray> tickPositions;
  vtkNew<vtkStringArray> tickLabels;
  for (const std::vector<double>& mantissas :
    { std::vector<double>{ 1.0, 2.0, 5.0 }, std::vector<double>{ 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0 } })
  {
    tickPositions->Reset();
    tickLabels->Reset();
    for (int decade = static_cast<int>(std::floor(logMin)); decade <= static_cast<int>(std::ceil(logMax)); ++decade)
    {
      for (const double mantissa : mantissas)
      {
        const double position = decade + std::log10(mantissa);
        if (position >= logMin && position <= logMax)
        {
          std::ostringstream label;
          label << mantissa * std::pow(10.0, decade);
          tickPositions->InsertNextValue(position);
          tickLabels->InsertNextValue(label.str());
        }
      }
    }
    if (tickPositions->GetNumberOfTuples() >= 3)
    {
      break;
    }
  }
  axis->SetTitle(title);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetRange(logMin, logMax);
  axis->SetCustomTickPositions(tickPositions, tickLabels);
}

void writeChartPng(const OffscreenChart& chart, const std::filesystem::path& pngPath)
{
  chart.view->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(chart.window);
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  // The same checked write as every other PNG (writePng): a failed write is an InputError naming the file.
  vtkImageData* pixels = grab->GetOutput();
  int dimensions[3] = { 0, 0, 0 };
  pixels->GetDimensions(dimensions);
  SL_CHECK_MSG(pixels->GetScalarType() == VTK_UNSIGNED_CHAR && pixels->GetNumberOfScalarComponents() == 3,
    "chart read-back is not 8-bit RGB");
  // vtkImageData and Image share the bottom-up row order.
  ImageU8 image(dimensions[0], dimensions[1], 3);
  std::memcpy(image.data.data(), pixels->GetScalarPointer(), image.data.size());
  writePng(pngPath, image);
}

} // namespace sl
