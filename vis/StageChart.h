// The stage-time chart of `shadowlab bench`: one horizontal bar per configuration, stacked from its pipeline stages'
// median GPU times (G-buffer, focus, shadow map, each light-space structure, technique, shading, ...) in pipeline
// order, so that a reader sees which stage a technique's frame went to (vtkChartXY, offscreen through an EGL window).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct StageBar
{
  std::string label;               // the configuration (technique, settings) and its frame time's spread
  std::vector<double> stageMs;     // one value per StageChartSpec::stages entry, 0 where the stage did not run
};

struct StageChartSpec
{
  std::string title;
  std::vector<std::string> stages; // stacking (and legend) order
  std::string valueTitle = "GPU time per stage (ms, median of the timed frames)";
};

// The chart grows with the bars (about 26 px each). Throws GraphicsError without an EGL context, InputError when the
// PNG cannot be written or a bar's values do not match the stages.
void writeStageChart(const std::vector<StageBar>& bars, const StageChartSpec& spec, const std::filesystem::path& pngPath);

} // namespace sl
