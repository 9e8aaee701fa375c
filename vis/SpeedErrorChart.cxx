#include "vis/SpeedErrorChart.h"

#include "vis/ChartSupport.h"
#include "vis/ColorMap.h"

#include <vtkAxis.h>
#include <vtkChartXY.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkTable.h>

#include <algorithm>
#include <cmath>
#include <map>

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
  const OffscreenChart offscreen = makeOffscreenChart(title);
  vtkChartXY* chart = offscreen.chart;
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
  setLogAxis(chart->GetAxis(vtkAxis::BOTTOM), logMin - 0.1, logMax + 0.1, "frame GPU time (ms, log scale)");
  vtkAxis* errorAxis = chart->GetAxis(vtkAxis::LEFT);
  errorAxis->SetTitle("RMSE of visibility vs ray-traced reference");
  errorAxis->SetBehavior(vtkAxis::FIXED);
  errorAxis->SetRange(0.0, rmseMax > 0.0 ? 1.08 * rmseMax : 1.0);
  writeChartPng(offscreen, pngPath);
}

} // namespace sl
