#include "metrics/DepthProfile.h"

#include "core/Error.h"
#include "core/Parse.h"
#include "frame/FrameResult.h"
#include "lightspace/PerspectiveWarp.h"
#include "lightspace/ShadowMapMath.h"

#include <algorithm>
#include <cmath>

namespace sl
{
namespace
{

// The value at fraction q of the sorted values (nearest rank).
double quantile(const std::vector<double>& sorted, double q)
{
  const std::size_t index = std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())));
  return sorted[index];
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return quantile(values, 0.5);
}

} // namespace

double Fig12ClosedForm::at(double depth) const
{
  return pixelsPerUnit / texelsAcrossBody * closedFormWarpAliasing(depth, zNear, zFar, n);
}

double Fig12ClosedForm::logarithmic() const
{
  return pixelsPerUnit / texelsAcrossBody * std::log(zFar / zNear);
}

std::optional<Fig12ClosedForm> fig12ClosedForm(const FrameResult& frame, const std::string& buffer)
{
  if ((buffer != "texel_ratio_t" && buffer != "perspective_factor") || !frame.lightView ||
    !frame.lightView->warp.active() || std::abs(frame.lightView->warp.gammaDeg - 90.0) > 0.5)
  {
    return std::nullopt;
  }
  const LightView& view = *frame.lightView;
  const PerspectiveWarp& warp = view.warp;
  Fig12ClosedForm form;
  form.zNear = warp.zNear;
  form.zFar = warp.zFar;
  form.n = warp.n;
  // The survey's p is the screen at unit distance; the t axis's step is vertical on the screen for view ⟂ light.
  form.pixelsPerUnit = 0.5 * frame.resolution.y * frame.camera.clipFromView[1][1];
  // z_n and z_f on the view axis land on the two ends of the focused body along the map's t axis.
  const glm::dmat4 worldFromCamera = glm::inverse(frame.camera.viewFromWorld);
  const glm::dvec3 eye(worldFromCamera[3]);
  const glm::dvec3 forward = -glm::normalize(glm::dvec3(worldFromCamera[2]));
  form.texelsAcrossBody = std::abs(projectToShadowMap(view, eye + warp.zFar * forward).uvTexels.y -
    projectToShadowMap(view, eye + warp.zNear * forward).uvTexels.y);
  if (!(form.texelsAcrossBody > 0.0) || !(form.pixelsPerUnit > 0.0))
  {
    return std::nullopt;
  }
  return form;
}

DepthProfile depthProfile(const FrameResult& frame, const DepthProfileSettings& settings)
{
  const NamedImage* values = frame.find(settings.buffer);
  if (values == nullptr || values->image.components != 1)
  {
    throw InputError("--depth-profile " + settings.buffer + ": the frame of " + frame.technique +
      " has no one-component buffer of that name");
  }
  if (settings.bins < 1)
  {
    throw InputError(format("--depth-bins ", settings.bins, ": must be >= 1"));
  }
  const bool ownRange = settings.nearDepth == 0.0 && settings.farDepth == 0.0;
  if (!ownRange && !(settings.nearDepth > 0.0 && settings.farDepth > settings.nearDepth))
  {
    throw InputError(format("--depth-range ", settings.nearDepth, ",", settings.farDepth, ": expected 0 < near < far"));
  }
  SL_CHECK_MSG(frame.find("depth") && frame.find("coverage"), "a frame of ", frame.technique, " without depth or coverage");
  const ImageF& depth = frame.find("depth")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  struct Sample
  {
    double depth;
    double value;
  };
  std::vector<Sample> samples;
  for (int y = 0; y < depth.height; ++y)
  {
    for (int x = 0; x < depth.width; ++x)
    {
      const double value = values->image.at(x, y);
      const double z = depth.at(x, y);
      if (coverage.at(x, y) > 0.5f && std::isfinite(value) && value != 0.0 && z > 0.0 &&
        (ownRange || (z >= settings.nearDepth && z <= settings.farDepth)))
      {
        samples.push_back({ z, value });
      }
    }
  }
  DepthProfile profile;
  profile.buffer = settings.buffer;
  profile.closedForm = fig12ClosedForm(frame, settings.buffer);
  double nearDepth = settings.nearDepth;
  double farDepth = settings.farDepth;
  if (ownRange)
  {
    nearDepth = farDepth = samples.empty() ? 1.0 : samples.front().depth;
    for (const Sample& sample : samples)
    {
      nearDepth = std::min(nearDepth, sample.depth);
      farDepth = std::max(farDepth, sample.depth);
    }
    farDepth = std::max(farDepth, nearDepth * (1.0 + 1e-9));
  }
  const double logRatio = std::log(farDepth / nearDepth);
  std::vector<std::vector<Sample>> binned(settings.bins);
  for (const Sample& sample : samples)
  {
    const int bin = static_cast<int>(std::floor(std::log(sample.depth / nearDepth) / logRatio * settings.bins));
    binned[std::clamp(bin, 0, settings.bins - 1)].push_back(sample);
  }
  for (int b = 0; b < settings.bins; ++b)
  {
    DepthBin bin;
    bin.nearDepth = nearDepth * std::exp(logRatio * b / settings.bins);
    bin.farDepth = nearDepth * std::exp(logRatio * (b + 1) / settings.bins);
    const std::vector<Sample>& inBin = binned[b];
    bin.pixels = inBin.size();
    if (!inBin.empty())
    {
      std::vector<double> depths, sorted, overClosedForm;
      for (const Sample& sample : inBin)
      {
        depths.push_back(sample.depth);
        sorted.push_back(sample.value);
        if (profile.closedForm)
        {
          overClosedForm.push_back(sample.value / profile.closedForm->at(sample.depth));
        }
      }
      std::sort(sorted.begin(), sorted.end());
      bin.depthMedian = median(depths);
      bin.lowerQuartile = quantile(sorted, 0.25);
      bin.median = quantile(sorted, 0.5);
      bin.upperQuartile = quantile(sorted, 0.75);
      if (profile.closedForm)
      {
        bin.closedForm = profile.closedForm->at(bin.depthMedian);
        bin.medianOverClosedForm = median(overClosedForm);
      }
    }
    profile.bins.push_back(bin);
  }
  return profile;
}

DepthProfileSettings depthProfileSettings(const std::string& buffer, int bins, const std::string& range)
{
  DepthProfileSettings settings;
  settings.buffer = buffer;
  settings.bins = bins;
  if (bins < 1)
  {
    throw InputError(format("--depth-bins ", bins, ": must be >= 1"));
  }
  if (!range.empty())
  {
    const std::size_t comma = range.find(',');
    const std::optional<double> nearDepth = comma == std::string::npos ? std::nullopt : parseNumber(range.substr(0, comma));
    const std::optional<double> farDepth = comma == std::string::npos ? std::nullopt : parseNumber(range.substr(comma + 1));
    if (!nearDepth || !farDepth || !(*nearDepth > 0.0 && *farDepth > *nearDepth))
    {
      throw InputError("--depth-range '" + range + "': expected near,far eye depths with 0 < near < far");
    }
    settings.nearDepth = *nearDepth;
    settings.farDepth = *farDepth;
  }
  return settings;
}

nlohmann::json depthProfileJson(const DepthProfile& profile)
{
  nlohmann::json bins = nlohmann::json::array();
  for (const DepthBin& bin : profile.bins)
  {
    nlohmann::json row = { { "near_depth", bin.nearDepth }, { "far_depth", bin.farDepth }, { "pixels", bin.pixels },
      { "depth_median", bin.depthMedian }, { "lower_quartile", bin.lowerQuartile }, { "median", bin.median },
      { "upper_quartile", bin.upperQuartile } };
    if (bin.closedForm)
    {
      row["closed_form"] = *bin.closedForm;
      row["median_over_closed_form"] = *bin.medianOverClosedForm;
    }
    bins.push_back(row);
  }
  nlohmann::json json = { { "buffer", profile.buffer }, { "bins", bins } };
  if (profile.closedForm)
  {
    const Fig12ClosedForm& form = *profile.closedForm;
    json["closed_form"] = { { "source", "survey Fig. 12 (Eq. 1, view perpendicular to the light)" },
      { "z_near", form.zNear }, { "z_far", form.zFar },
      { "n", std::isfinite(form.n) ? nlohmann::json(form.n) : nlohmann::json() },
      { "pixels_per_unit", form.pixelsPerUnit }, { "texels_across_body", form.texelsAcrossBody },
      { "logarithmic", form.logarithmic() } };
  }
  return json;
}

} // namespace sl
