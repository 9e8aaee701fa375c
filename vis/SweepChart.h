// The light-size (or any numeric scene value) sweep chart of `shadowlab bench --scene-sweep`: one line per
// technique of a measure (frame GPU time, RMSE) against the swept value, on logarithmic axes where asked
// (vtkChartXY, offscreen through an EGL window).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct SweepPoint
{
  std::string series; // technique (and its settings)
  double parameter = 0.0; // the swept scene value
  double value = 0.0;     // the measure
};

struct SweepAxes
{
  std::string parameterTitle; // "light size (world units)"
  std::string valueTitle;     // "frame GPU time (ms)"
  bool logParameter = false;
  bool logValue = false;
  // The legend at the bottom right instead of the top right: where a chart's lines rise to the right (cost against
  // size), the top right holds their last points.
  bool legendBottom = false;
};

// Throws GraphicsError without an EGL context, InputError when the PNG cannot be written or a logarithmic
// axis meets a value <= 0.
void writeSweepChart(const std::vector<SweepPoint>& points, const std::string& title, const SweepAxes& axes,
  const std::filesystem::path& pngPath);

} // namespace sl
