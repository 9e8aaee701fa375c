#include "vis/SweepChart.h"

#include "core/Error.h"
#include "vis/ChartSupport.h"
#include "vis/ColorMap.h"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkTable.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace sl
{

void writeSweepChart(const std::vector<SweepPoint>& points, const std::string& title, const SweepAxes& axes,
  const std::filesystem::path& pngPath)
{
  const auto axisValue = [&](double value, bool logarithmic, const std::string& what) {
    if (logarithmic && !(value > 0.0))
    {
      throw InputError(format(pngPath.string(), ": ", what, " ", value, " cannot go on a logarithmic axis"));
    }
    return logarithmic ? std::log10(value) : value;
  };
  const OffscreenChart offscreen = makeOffscreenChart(title);
  if (axes.legendBottom)
  {
    offscreen.chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::BOTTOM);
  }
  std::map<std::string, std::vector<SweepPoint>> bySeries;
  for (const SweepPoint& point : points)
  {
    bySeries[point.series].push_back(point);
  }
  double xMin = 1e300;
  double xMax = -1e300;
  double yMin = 1e300;
  double yMax = -1e300;
  long long colorIndex = 0;
  for (auto& [series, seriesPoints] : bySeries)
  {
    std::sort(seriesPoints.begin(), seriesPoints.end(),
      [](const SweepPoint& a, const SweepPoint& b) { return a.parameter < b.parameter; });
    vtkNew<vtkDoubleArray> x;
    x->SetName(axes.parameterTitle.c_str());
    vtkNew<vtkDoubleArray> y;
    y->SetName(series.c_str());
    for (const SweepPoint& point : seriesPoints)
    {
      const double px = axisValue(point.parameter, axes.logParameter, axes.parameterTitle);
      const double py = axisValue(point.value, axes.logValue, axes.valueTitle);
      x->InsertNextValue(px);
      y->InsertNextValue(py);
      xMin = std::min(xMin, px);
      xMax = std::max(xMax, px);
      yMin = std::min(yMin, py);
      yMax = std::max(yMax, py);
    }
    vtkNew<vtkTable> table;
    table->AddColumn(x);
    table->AddColumn(y);
    const RgbColor color = ColorMap::categoryColor(colorIndex++);
    vtkPlot* line = offscreen.chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    line->SetColor(static_cast<unsigned char>(255 * color[0]), static_cast<unsigned char>(255 * color[1]),
      static_cast<unsigned char>(255 * color[2]), 255);
    line->SetWidth(2.0f);
    if (auto* markers = vtkPlotPoints::SafeDownCast(line))
    {
      markers->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      markers->SetMarkerSize(8.0f);
    }
  }
  if (points.empty())
  {
    xMin = yMin = 0.0;
    xMax = yMax = 1.0;
  }
  const auto setAxis = [](vtkAxis* axis, double low, double high, bool logarithmic, const std::string& axisTitle) {
    const double margin = logarithmic ? 0.1 : 0.05 * std::max(high - low, 1e-12);
    if (logarithmic)
    {
      setLogAxis(axis, low - margin, high + margin, axisTitle + " (log scale)");
      return;
    }
    axis->SetTitle(axisTitle);
    axis->SetBehavior(vtkAxis::FIXED);
    axis->SetRange(std::min(0.0, low), high + margin);
  };
  setAxis(offscreen.chart->GetAxis(vtkAxis::BOTTOM), xMin, xMax, axes.logParameter, axes.parameterTitle);
  setAxis(offscreen.chart->GetAxis(vtkAxis::LEFT), yMin, yMax, axes.logValue, axes.valueTitle);
  writeChartPng(offscreen, pngPath);
}

} // namespace sl
