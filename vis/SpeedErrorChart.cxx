#include "vis/SpeedErrorChart.h"

#include "vis/ChartSupport.h"
#include "vis/ColorMap.h"
#include "vis/vtkSLPointLabels.h"

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
#include <sstream>

namespace sl
{
namespace
{

// Both axes are logarithmic: plotted as log10 values with decade ticks labelled in the original units (VTK 9.1's
// vtkAxis::SetLogScale draws no plots offscreen here).
double speedErrorLogTime(double timeMs)
{
  return std::log10(std::max(timeMs, 1e-6));
}

double speedErrorLogError(double error, double floor)
{
  return std::log10(std::max(error, floor));
}

vtkSmartPointer<vtkTable> makeSpeedErrorTable(const std::vector<ChartPoint>& points, const std::vector<std::size_t>& indices,
  const std::string& seriesName, double errorFloor)
{
  vtkNew<vtkDoubleArray> time;
  time->SetName("time_ms");
  vtkNew<vtkDoubleArray> error;
  error->SetName(seriesName.c_str());
  for (const std::size_t index : indices)
  {
    time->InsertNextValue(speedErrorLogTime(points[index].timeMs));
    error->InsertNextValue(speedErrorLogError(points[index].rmse, errorFloor));
  }
  auto table = vtkSmartPointer<vtkTable>::New();
  table->AddColumn(time);
  table->AddColumn(error);
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

void writeSpeedErrorChart(const std::vector<ChartPoint>& points, const std::string& title,
  const std::filesystem::path& pngPath, const SpeedErrorAxes& axes)
{
  const OffscreenChart offscreen = makeOffscreenChart(title);
  vtkChartXY* chart = offscreen.chart;
  // Series in order of first appearance (the bench's technique order); a series' points in the order given (a
  // sweep's order), so that a line joins them as swept.
  std::vector<std::string> seriesOrder;
  std::map<std::string, std::vector<std::size_t>> bySeries;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!bySeries.count(points[i].series))
    {
      seriesOrder.push_back(points[i].series);
    }
    bySeries[points[i].series].push_back(i);
  }
  const double floor = axes.errorFloor;
  long long colorIndex = 0;
  std::vector<double> labelX;
  std::vector<double> labelY;
  std::vector<std::string> labelTexts;
  for (const std::string& series : seriesOrder)
  {
    const std::vector<std::size_t>& indices = bySeries.at(series);
    const RgbColor color = ColorMap::categoryColor(colorIndex++);
    vtkPlot* plot = chart->AddPlot(indices.size() > 1 ? vtkChart::LINE : vtkChart::POINTS);
    plot->SetInputData(makeSpeedErrorTable(points, indices, series, floor), 0, 1);
    plot->SetColor(static_cast<unsigned char>(255 * color[0]), static_cast<unsigned char>(255 * color[1]),
      static_cast<unsigned char>(255 * color[2]), 255);
    plot->SetWidth(1.5f);
    if (auto* pointsPlot = vtkPlotPoints::SafeDownCast(plot))
    {
      // The palette has ten colours: the next ten series are squares, then diamonds, so no two series look alike.
      const int shapes[] = { vtkPlotPoints::CIRCLE, vtkPlotPoints::SQUARE, vtkPlotPoints::DIAMOND };
      pointsPlot->SetMarkerStyle(shapes[((colorIndex - 1) / 10) % 3]);
      pointsPlot->SetMarkerSize(10.0f);
    }
    for (const std::size_t index : indices)
    {
      if (!points[index].label.empty())
      {
        labelX.push_back(speedErrorLogTime(points[index].timeMs));
        labelY.push_back(speedErrorLogError(points[index].rmse, floor));
        labelTexts.push_back(points[index].label);
      }
    }
  }
  const std::vector<std::size_t> front = paretoFront(points);
  if (front.size() > 1)
  {
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(makeSpeedErrorTable(points, front, "Pareto front", floor), 0, 1);
    line->SetColor(60, 60, 60, 255);
    line->SetWidth(2.0f);
    line->GetPen()->SetLineType(vtkPen::DASH_LINE);
  }
  if (!labelTexts.empty())
  {
    vtkNew<vtkSLPointLabels> labels;
    labels->SetLabels(labelX, labelY, labelTexts);
    chart->AddPlot(labels);
  }
  double timeMin = 1e300;
  double timeMax = -1e300;
  double errorMin = 1e300;
  double errorMax = -1e300;
  bool floored = false;
  for (const ChartPoint& point : points)
  {
    timeMin = std::min(timeMin, speedErrorLogTime(point.timeMs));
    timeMax = std::max(timeMax, speedErrorLogTime(point.timeMs));
    errorMin = std::min(errorMin, speedErrorLogError(point.rmse, floor));
    errorMax = std::max(errorMax, speedErrorLogError(point.rmse, floor));
    floored = floored || point.rmse < floor;
  }
  if (points.empty())
  {
    timeMin = errorMin = 0.0;
    timeMax = errorMax = 1.0;
  }
  // Room on the right for the labels and the legend.
  setLogAxis(chart->GetAxis(vtkAxis::BOTTOM), timeMin - 0.1, timeMax + 0.1 + 0.25 * std::max(timeMax - timeMin, 0.3),
    "frame GPU time (ms, median, log scale)");
  std::ostringstream errorTitle;
  errorTitle << axes.errorTitle << " (log scale" << (floored ? ", values under " : "");
  if (floored)
  {
    errorTitle << floor << " drawn at it";
  }
  errorTitle << ")";
  setLogAxis(chart->GetAxis(vtkAxis::LEFT), errorMin - 0.15, errorMax + 0.15, errorTitle.str());
  writeChartPng(offscreen, pngPath);
}

} // namespace sl
