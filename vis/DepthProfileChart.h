// The depth-profile chart of `shadowlab bench --depth-profile` (the survey's Fig. 12 drawn from measurements): per
// configuration its bins' medians as markers and, where it has one, its closed form as a line of the same colour,
// plus lines of closed forms that belong to no configuration (logarithmic warping), against the eye's depth on
// linear axes as the survey draws it (vtkChartXY, offscreen through an EGL window).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sl
{

struct DepthProfileSeries
{
  std::string name;
  std::vector<double> depths;      // measured: the bins' median depths
  std::vector<double> medians;     //           and medians (empty: a closed form alone)
  std::vector<double> curveDepths; // the closed form, drawn as a line (empty: none)
  std::vector<double> curveValues;
};

// Throws GraphicsError without an EGL context, InputError when the PNG cannot be written.
void writeDepthProfileChart(const std::vector<DepthProfileSeries>& series, const std::string& title,
  const std::string& valueTitle, const std::filesystem::path& pngPath);

} // namespace sl
