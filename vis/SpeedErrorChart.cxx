#include "vis/SpeedErrorChart.h"

#include "core/Error.h"
#include "gl/vtkSLEglRenderWindow.h"
#include "vis/ColorMap.h"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <map>
#include <numeric>

namespace sl
{
namespace
{

vtkSmartPointer<vtkTable> makeTable(const std::vector<ChartPoint>& points, const std::vector<std::size_t>& indices,
  const std::string& seriesName)
{
  vtkNew<vtkDoubleArray> time;
  time->SetName("time_ms");
  vtkNew<vtkDoubleArray> rmse;
  rmse->SetName(seriesName.c_str());
  for (const std::size_t index : indices)
  {
    // The time axis is logarithmic: plotted as log10(ms) with decade ticks labelled in ms (VTK 9.1's
    // vtkAxis::SetLogScale draws no plots offscreen here).
    time->InsertNextValue(std::log10(std::max(points[index].timeMs, 1e-6)));
    rmse->InsertNextValue(points[index].rmse);
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(time);
  table->AddColumn(rmse);
  return table;
}

} // namespace

std::vector<std::size_t> paretoFront(const std::vector<ChartPoint>& points)
{
  std::vector<std::size_t> front;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const bool dominated = std::any_of(points.begin(), points.end(), [&](const ChartPoint& other) {
      return other.timeMs <= points[i].timeMs && other.rmse <= points[i].rmse &&
        (other.timeMs < points[i].timeMs || other.rmse < points[i].rmse);
    });
    if (!dominated)
    {
      front.push_back(i);
    }
  }
  std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) { return points[a].timeMs < points[b].timeMs; });
  return front;
}

void writeSpeedErrorChart(const std::vector<ChartPoint>& points, const std::string& title, const std::filesystem::path& pngPath)
{
  vtkNew<vtkSLEglRenderWindow> window;
  window->InitializeOffscreen(960, 640);
  vtkNew<vtkContextView> view;
  view->SetRenderWindow(window);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);

  std::map<std::string, std::vector<std::size_t>> bySeries;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    bySeries[points[i].series].push_back(i);
  }
  long long colorIndex = 0;
  for (const auto& [series, indices] : bySeries)
  {
    const RgbColor color = ColorMap::categoryColor(colorIndex++);
    vtkPlot* plot = chart->AddPlot(vtkChart::POINTS);
    plot->SetInputData(makeTable(points, indices, series), 0, 1);
    plot->SetColor(static_cast<unsigned char>(255 * color[0]), static_cast<unsigned char>(255 * color[1]),
      static_cast<unsigned char>(255 * color[2]), 255);
    if (auto* pointsPlot = vtkPlotPoints::SafeDownCast(plot))
    {
      pointsPlot->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      pointsPlot->SetMarkerSize(10.0f);
    }
  }
  const std::vector<std::size_t> front = paretoFront(points);
  if (front.size() > 1)
  {
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(makeTable(points, front, "Pareto front"), 0, 1);
    line->SetColor(60, 60, 60, 255);
    line->SetWidth(2.0f);
    line->GetPen()->SetLineType(vtkPen::DASH_LINE);
  }
  double logMin = 1e300;
  double logMax = -1e300;
  double rmseMax = 0.0;
  for (const ChartPoint& point : points)
  {
    logMin = std::min(logMin, std::log10(std::max(point.timeMs, 1e-6)));
    logMax = std::max(logMax, std::log10(std::max(point.timeMs, 1e-6)));
    rmseMax = std::max(rmseMax, point.rmse);
  }
  if (points.empty())
  {
    logMin = 0.0;
    logMax = 1.0;
  }
  logMin -= 0.1;
  logMax += 0.1;
  vtkNew<vtkDoubleArray> tickPositions;
  vtkNew<vtkStringArray> tickLabels;
  // Ticks at 1, 2, 5 x 10^k; over a narrow range (fewer than three of those) at every integer mantissa.
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
  vtkAxis* timeAxis = chart->GetAxis(vtkAxis::BOTTOM);
  timeAxis->SetTitle("frame GPU time (ms, log scale)");
  timeAxis->SetBehavior(vtkAxis::FIXED);
  timeAxis->SetRange(logMin, logMax);
  timeAxis->SetCustomTickPositions(tickPositions, tickLabels);
  vtkAxis* errorAxis = chart->GetAxis(vtkAxis::LEFT);
  errorAxis->SetTitle("RMSE of visibility vs ray-traced reference");
  errorAxis->SetBehavior(vtkAxis::FIXED);
  errorAxis->SetRange(0.0, rmseMax > 0.0 ? 1.08 * rmseMax : 1.0);

  view->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(pngPath.string().c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0 || !std::filesystem::is_regular_file(pngPath))
  {
    throw InputError(pngPath.string() + ": cannot write the chart");
  }
}

} // namespace sl
