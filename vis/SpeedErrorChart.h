// The speed-against-error scatter plot of `shadowlab bench` (vtkChartXY, rendered offscreen through an
// EGL window): frame GPU time on a log axis, RMSE against the ray-traced reference on the other, one
// point series per technique, and the Pareto front (configurations no other beats on both) as a line.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct ChartPoint
{
  std::string series; // technique
  double timeMs = 0.0;
  double rmse = 0.0;
};

// Indices of the points on the Pareto front (no other point has both lower-or-equal time and
// lower-or-equal RMSE with one strictly lower), sorted by time.
std::vector<std::size_t> paretoFront(const std::vector<ChartPoint>& points);

// Throws GraphicsError without an EGL context, InputError when the PNG cannot be written.
void writeSpeedErrorChart(const std::vector<ChartPoint>& points, const std::string& title, const std::filesystem::path& pngPath);

} // namespace sl
