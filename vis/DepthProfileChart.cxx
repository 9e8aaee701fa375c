#include "vis/DepthProfileChart.h"

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

namespace sl
{
namespace
{

vtkPlot* addPlot(vtkChartXY* chart, int type, const std::string& name, const std::vector<double>& xs,
  const std::vector<double>& ys, const RgbColor& color)
{
  vtkNew<vtkDoubleArray> x;
  x->SetName("eye depth");
  vtkNew<vtkDoubleArray> y;
  y->SetName(name.c_str());
  for (std::size_t i = 0; i < xs.size(); ++i)
  {
    x->InsertNextValue(xs[i]);
    y->InsertNextValue(ys[i]);
  }
  vtkNew<vtkTable> table;
  table->AddColumn(x);
  table->AddColumn(y);
  vtkPlot* plot = chart->AddPlot(type);
  plot->SetInputData(table, 0, 1);
  plot->SetColor(static_cast<unsigned char>(255 * color[0]), static_cast<unsigned char>(255 * color[1]),
    static_cast<unsigned char>(255 * color[2]), 255);
  return plot;
}

} // namespace

void writeDepthProfileChart(const std::vector<DepthProfileSeries>& series, const std::string& title,
  const std::string& valueTitle, const std::filesystem::path& pngPath)
{
  const OffscreenChart offscreen = makeOffscreenChart(title);
  // Top centre: Fig. 12's curves climb at the left (uniform) and the right (PSM) edges.
  offscreen.chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::CENTER);
  double depthMax = 1.0;
  double valueMax = 1.0;
  long long colorIndex = 0;
  for (const DepthProfileSeries& one : series)
  {
    const RgbColor color = ColorMap::categoryColor(colorIndex++);
    if (!one.curveDepths.empty())
    {
      vtkPlot* line = addPlot(offscreen.chart, vtkChart::LINE, one.name + (one.depths.empty() ? "" : " (closed form)"),
        one.curveDepths, one.curveValues, color);
      line->SetWidth(2.0f);
      if (auto* markers = vtkPlotPoints::SafeDownCast(line))
      {
        markers->SetMarkerStyle(vtkPlotPoints::NONE);
      }
      depthMax = std::max(depthMax, *std::max_element(one.curveDepths.begin(), one.curveDepths.end()));
      valueMax = std::max(valueMax, *std::max_element(one.curveValues.begin(), one.curveValues.end()));
    }
    if (!one.depths.empty())
    {
      vtkPlot* points = addPlot(offscreen.chart, vtkChart::POINTS, one.name + " (measured median)", one.depths,
        one.medians, color);
      if (auto* markers = vtkPlotPoints::SafeDownCast(points))
      {
        markers->SetMarkerStyle(vtkPlotPoints::CIRCLE);
        markers->SetMarkerSize(9.0f);
      }
      depthMax = std::max(depthMax, *std::max_element(one.depths.begin(), one.depths.end()));
      valueMax = std::max(valueMax, *std::max_element(one.medians.begin(), one.medians.end()));
    }
  }
  vtkAxis* bottom = offscreen.chart->GetAxis(vtkAxis::BOTTOM);
  bottom->SetTitle("eye depth z (world units)");
  bottom->SetBehavior(vtkAxis::FIXED);
  bottom->SetRange(0.0, 1.05 * depthMax);
  vtkAxis* left = offscreen.chart->GetAxis(vtkAxis::LEFT);
  left->SetTitle(valueTitle);
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(0.0, 1.05 * valueMax);
  writeChartPng(offscreen, pngPath);
}

} // namespace sl
