// The speed-against-error chart of `shadowlab bench` (vtkChartXY, rendered offscreen through an EGL window): frame
// GPU time and an error against the ray-traced reference, both on log axes (the soft techniques' errors are one to
// two decades under the hard ones': a linear axis squeezes them into its bottom few per cent). One series per
// technique and its fixed settings; the points of a sweep are joined in sweep order and each is labelled with its
// swept value. The Pareto front (configurations no other beats on both) is a dashed line.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct ChartPoint
{
  std::string series; // technique (and the settings no sweep varies)
  double timeMs = 0.0;
  double rmse = 0.0;  // the error plotted (RMSE, or penumbra RMSE)
  std::string label;  // the swept values of this point ("512", "psm 0"); empty when nothing is swept
};

// Indices of the points on the Pareto front (no other point has both lower-or-equal time and
// lower-or-equal RMSE with one strictly lower), sorted by time.
std::vector<std::size_t> paretoFront(const std::vector<ChartPoint>& points);

// Errors under `errorFloor` (an exact 0 included) are drawn at it and the axis title says so.
struct SpeedErrorAxes
{
  std::string errorTitle = "RMSE of visibility vs ray-traced reference";
  double errorFloor = 1e-4;
};

// Throws GraphicsError without an EGL context, InputError when the PNG cannot be written.
void writeSpeedErrorChart(const std::vector<ChartPoint>& points, const std::string& title,
  const std::filesystem::path& pngPath, const SpeedErrorAxes& axes = {});

} // namespace sl
