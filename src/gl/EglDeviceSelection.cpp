#include "gl/EglDeviceSelection.h"

#include "core/Error.h"

#include <cstdlib>
#include <optional>
#include <vector>

namespace sl
{
namespace
{

std::string environmentValue(const char* name)
{
  const char* value = std::getenv(name);
  return value ? value : "";
}

// A non-negative decimal index, or none ("GPU-8e1f...", a MIG name, "NoDevFiles", "").
std::optional<int> deviceIndexOf(const std::string& text)
{
  if (text.empty() || text.size() > 6 || text.find_first_not_of("0123456789") != std::string::npos)
  {
    return std::nullopt;
  }
  return std::atoi(text.c_str());
}

std::vector<std::string> commaItems(const std::string& text)
{
  std::vector<std::string> items;
  for (std::size_t start = 0; start <= text.size();)
  {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return items;
}

} // namespace

EglDeviceEnvironment eglDeviceEnvironment()
{
  return { environmentValue("SHADOWLAB_EGL_DEVICE"), environmentValue("SLURM_STEP_GPUS"),
    environmentValue("SLURM_JOB_GPUS"), environmentValue("CUDA_VISIBLE_DEVICES") };
}

EglDeviceSelection selectEglDevice(const EglDeviceEnvironment& environment, int hardwareDevices)
{
  if (!environment.explicitDevice.empty())
  {
    const std::optional<int> index = deviceIndexOf(environment.explicitDevice);
    if (hardwareDevices > 0 && (!index || *index >= hardwareDevices))
    {
      throw GraphicsError(format("SHADOWLAB_EGL_DEVICE=", environment.explicitDevice, ": expected an index of the ",
        hardwareDevices, " hardware EGL device(s), 0 to ", hardwareDevices - 1));
    }
    return { index.value_or(0), "SHADOWLAB_EGL_DEVICE=" + environment.explicitDevice, true };
  }
  const std::pair<const char*, const std::string*> assignments[] = { { "SLURM_STEP_GPUS", &environment.slurmStepGpus },
    { "SLURM_JOB_GPUS", &environment.slurmJobGpus }, { "CUDA_VISIBLE_DEVICES", &environment.cudaVisibleDevices } };
  for (const auto& [name, value] : assignments)
  {
    if (value->empty())
    {
      continue;
    }
    const std::vector<std::string> items = commaItems(*value);
    const std::optional<int> first = deviceIndexOf(items.front());
    const std::string source = std::string(name) + "=" + *value;
    if (!first)
    {
      // A UUID or MIG name: not an index of EGL's list; the driver shows such a process only its devices.
      return { 0, source + " (not an index: the first EGL device)", true };
    }
    if (*first < hardwareDevices || hardwareDevices == 0)
    {
      return { *first, source, true };
    }
    return { 0, source + format(" (EGL lists ", hardwareDevices, " device(s): the assigned ones, first)"), true };
  }
  return { 0, "default (no GPU assigned)", false };
}

} // namespace sl
