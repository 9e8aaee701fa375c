#include "vis/StageChart.h"

#include "core/Error.h"
#include "vis/ChartSupport.h"
#include "vis/ColorMap.h"

#include <vtkAxis.h>
#include <vtkColor.h>
#include <vtkColorSeries.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPlotBar.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <algorithm>
#include <array>

namespace sl
{
namespace
{

// Tableau 10 for the first ten stages, then the lighter companion of each (Tableau 20's pairs): a frame with a few
// structures has more than ten stages, and a repeated colour would merge two of them.
RgbColor stageChartColor(std::size_t stage)
{
  static const std::array<RgbColor, 10> lighter{ { { 0xae / 255.0, 0xc7 / 255.0, 0xe8 / 255.0 },
    { 0xff / 255.0, 0xbb / 255.0, 0x78 / 255.0 }, { 0x98 / 255.0, 0xdf / 255.0, 0x8a / 255.0 },
    { 0xff / 255.0, 0x98 / 255.0, 0x96 / 255.0 }, { 0xc5 / 255.0, 0xb0 / 255.0, 0xd5 / 255.0 },
    { 0xc4 / 255.0, 0x9c / 255.0, 0x94 / 255.0 }, { 0xf7 / 255.0, 0xb6 / 255.0, 0xd2 / 255.0 },
    { 0xc7 / 255.0, 0xc7 / 255.0, 0xc7 / 255.0 }, { 0xdb / 255.0, 0xdb / 255.0, 0x8d / 255.0 },
    { 0x9e / 255.0, 0xda / 255.0, 0xe5 / 255.0 } } };
  return stage < 10 ? ColorMap::categoryColor(static_cast<long long>(stage)) : lighter[(stage - 10) % 10];
}

} // namespace

void writeStageChart(const std::vector<StageBar>& bars, const StageChartSpec& spec, const std::filesystem::path& pngPath)
{
  for (const StageBar& bar : bars)
  {
    if (bar.stageMs.size() != spec.stages.size())
    {
      throw InputError(format(pngPath.string(), ": bar '", bar.label, "' has ", bar.stageMs.size(), " stage times for ",
        spec.stages.size(), " stages"));
    }
  }
  const int height = std::max(480, 200 + 26 * static_cast<int>(bars.size()));
  const OffscreenChart offscreen = makeOffscreenChart(spec.title, 1100, height);
  // Bars top to bottom in the order given: position n - 1 - i on the vertical axis.
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> position;
  position->SetName("configuration");
  for (std::size_t i = 0; i < bars.size(); ++i)
  {
    position->InsertNextValue(static_cast<double>(bars.size() - 1 - i));
  }
  table->AddColumn(position);
  double longest = 0.0;
  for (std::size_t s = 0; s < spec.stages.size(); ++s)
  {
    vtkNew<vtkDoubleArray> stage;
    stage->SetName(spec.stages[s].c_str());
    for (const StageBar& bar : bars)
    {
      stage->InsertNextValue(std::max(0.0, bar.stageMs[s]));
    }
    table->AddColumn(stage);
  }
  for (const StageBar& bar : bars)
  {
    double total = 0.0;
    for (const double ms : bar.stageMs)
    {
      total += std::max(0.0, ms);
    }
    longest = std::max(longest, total);
  }
  auto* plot = vtkPlotBar::SafeDownCast(offscreen.chart->AddPlot(vtkChart::BAR));
  SL_CHECK_MSG(plot != nullptr, "vtkChartXY made no bar plot");
  plot->SetOrientation(vtkPlotBar::HORIZONTAL);
  plot->SetInputData(table);
  plot->SetInputArray(0, "configuration");
  for (std::size_t s = 0; s < spec.stages.size(); ++s)
  {
    plot->SetInputArray(static_cast<int>(s) + 1, spec.stages[s]);
  }
  vtkNew<vtkColorSeries> colors;
  colors->SetColorSchemeByName("shadowlab stages");
  colors->ClearColors();
  for (std::size_t s = 0; s < spec.stages.size(); ++s)
  {
    const RgbColor color = stageChartColor(s);
    colors->AddColor(vtkColor3ub(static_cast<unsigned char>(255 * color[0]), static_cast<unsigned char>(255 * color[1]),
      static_cast<unsigned char>(255 * color[2])));
  }
  plot->SetColorSeries(colors);
  plot->SetWidth(0.7f);

  vtkNew<vtkDoubleArray> tickPositions;
  vtkNew<vtkStringArray> tickLabels;
  for (std::size_t i = 0; i < bars.size(); ++i)
  {
    tickPositions->InsertNextValue(static_cast<double>(bars.size() - 1 - i));
    tickLabels->InsertNextValue(bars[i].label);
  }
  vtkAxis* configurationAxis = offscreen.chart->GetAxis(vtkAxis::LEFT);
  configurationAxis->SetTitle("");
  configurationAxis->SetBehavior(vtkAxis::FIXED);
  configurationAxis->SetRange(-0.6, static_cast<double>(bars.size()) - 0.4);
  configurationAxis->SetCustomTickPositions(tickPositions, tickLabels);
  vtkAxis* timeAxis = offscreen.chart->GetAxis(vtkAxis::BOTTOM);
  timeAxis->SetTitle(spec.valueTitle);
  timeAxis->SetBehavior(vtkAxis::FIXED);
  timeAxis->SetRange(0.0, longest > 0.0 ? 1.35 * longest : 1.0); // room for the legend, top right
  writeChartPng(offscreen, pngPath);
}

} // namespace sl
