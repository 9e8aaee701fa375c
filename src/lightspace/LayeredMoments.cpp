#include "lightspace/LayeredMoments.h"

#include <algorithm>
#include <cmath>

namespace sl
{

namespace
{

// The shader's uniforms are float: the twin uses the same rounded ends.
double layeredFloatEnd(double end)
{
  return static_cast<double>(static_cast<float>(end));
}

} // namespace

std::vector<double> layeredUniformEnds(int layers, double nearDepth, double farDepth)
{
  std::vector<double> ends(static_cast<std::size_t>(layers) + 1);
  const double width = (farDepth - nearDepth) / layers;
  for (int i = 0; i <= layers; ++i)
  {
    ends[static_cast<std::size_t>(i)] = layeredFloatEnd(i == layers ? farDepth : nearDepth + i * width);
  }
  return ends;
}

int layeredHistogramBin(double depth, double nearDepth, double farDepth)
{
  if (!(depth <= farDepth) || depth < nearDepth)
  {
    return -1;
  }
  const double position = (depth - nearDepth) / (farDepth - nearDepth) * layeredHistogramBins;
  return std::clamp(static_cast<int>(std::floor(position)), 0, layeredHistogramBins - 1);
}

std::vector<std::uint32_t> layeredDepthHistogram(const std::vector<float>& depths, double nearDepth, double farDepth)
{
  std::vector<std::uint32_t> histogram(layeredHistogramBins, 0);
  for (const float depth : depths)
  {
    const int bin = layeredHistogramBin(depth, nearDepth, farDepth);
    if (bin >= 0)
    {
      ++histogram[static_cast<std::size_t>(bin)];
    }
  }
  return histogram;
}

std::vector<double> layeredGapEnds(const std::vector<std::uint32_t>& histogram, int layers, double nearDepth,
  double farDepth)
{
  const int bins = static_cast<int>(histogram.size());
  const double binWidth = (farDepth - nearDepth) / bins;
  int firstOccupied = bins;
  int lastOccupied = -1;
  for (int bin = 0; bin < bins; ++bin)
  {
    if (histogram[static_cast<std::size_t>(bin)] > 0)
    {
      firstOccupied = std::min(firstOccupied, bin);
      lastOccupied = bin;
    }
  }
  struct EmptyRun
  {
    int first;
    int length;
  };
  std::vector<EmptyRun> runs;
  for (int bin = firstOccupied + 1; bin < lastOccupied; ++bin)
  {
    if (histogram[static_cast<std::size_t>(bin)] == 0)
    {
      const int first = bin;
      while (bin < lastOccupied && histogram[static_cast<std::size_t>(bin)] == 0)
      {
        ++bin;
      }
      runs.push_back({ first, bin - first });
    }
  }
  std::stable_sort(runs.begin(), runs.end(), [](const EmptyRun& a, const EmptyRun& b) { return a.length > b.length; });
  std::vector<double> ends{ nearDepth, farDepth };
  for (std::size_t run = 0; run < runs.size() && static_cast<int>(ends.size()) < layers + 1; ++run)
  {
    ends.push_back(nearDepth + (runs[run].first + 0.5 * runs[run].length) * binWidth);
  }
  std::sort(ends.begin(), ends.end());
  // Fewer gaps than boundaries: halve the widest layer (the first of equals).
  while (static_cast<int>(ends.size()) < layers + 1)
  {
    std::size_t widest = 0;
    for (std::size_t i = 1; i + 1 < ends.size(); ++i)
    {
      widest = ends[i + 1] - ends[i] > ends[widest + 1] - ends[widest] ? i : widest;
    }
    ends.insert(ends.begin() + static_cast<std::ptrdiff_t>(widest) + 1, 0.5 * (ends[widest] + ends[widest + 1]));
  }
  for (double& end : ends)
  {
    end = layeredFloatEnd(end);
  }
  return ends;
}

DepthLayer depthLayer(int layer, const std::vector<double>& ends)
{
  return { ends[static_cast<std::size_t>(layer)], ends[static_cast<std::size_t>(layer) + 1] };
}

int depthLayerIndex(double depth, const std::vector<double>& ends)
{
  const int layers = static_cast<int>(ends.size()) - 1;
  int index = 0;
  for (int i = 1; i < layers; ++i)
  {
    index = depth >= ends[static_cast<std::size_t>(i)] ? i : index;
  }
  return index;
}

DepthLayer depthLayer(int layer, int layers, double nearDepth, double farDepth)
{
  return depthLayer(layer, layeredUniformEnds(layers, nearDepth, farDepth));
}

int depthLayerIndex(double depth, int layers, double nearDepth, double farDepth)
{
  return depthLayerIndex(depth, layeredUniformEnds(layers, nearDepth, farDepth));
}

double warpIntoLayer(double depth, const DepthLayer& layer)
{
  return std::clamp((depth - layer.nearEnd) / layer.width(), 0.0, 1.0);
}

} // namespace sl
