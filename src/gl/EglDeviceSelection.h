// Which EGL device (EGL_EXT_platform_device) a process renders on when a node has several GPUs (issue 32): the
// one its batch system assigned it. A pure function of the environment and the number of hardware EGL devices,
// so it is tested without a GPU; EglContext applies it and stats.json names the outcome (egl_device).
//
// In order: SHADOWLAB_EGL_DEVICE=N (an index among the hardware EGL devices, the explicit override), then the first
// GPU of SLURM_STEP_GPUS, SLURM_JOB_GPUS or CUDA_VISIBLE_DEVICES (Slurm sets them with --gres=gpu; the first two
// are the node's GPU indices, which gres.conf numbers like the NVIDIA driver's device order, the order in which
// NVIDIA's EGL enumerates its devices), else device 0. Where a job's cgroup hides the other GPUs, EGL lists only
// the assigned ones: an assigned index past the list is then taken by its position in the assignment.
#pragma once

#include <string>

namespace sl
{

struct EglDeviceEnvironment
{
  std::string explicitDevice;     // SHADOWLAB_EGL_DEVICE
  std::string slurmStepGpus;      // SLURM_STEP_GPUS
  std::string slurmJobGpus;       // SLURM_JOB_GPUS
  std::string cudaVisibleDevices; // CUDA_VISIBLE_DEVICES
};

EglDeviceEnvironment eglDeviceEnvironment(); // of this process

struct EglDeviceSelection
{
  int index = 0;      // among the hardware EGL devices
  std::string source; // "SHADOWLAB_EGL_DEVICE=1", "SLURM_STEP_GPUS=2,3", ..., or "default (no GPU assigned)"
  bool assigned = false; // chosen by the environment: no other device is tried when it fails
};

// Throws GraphicsError (one line naming SHADOWLAB_EGL_DEVICE) when the override is not an index in
// [0, hardwareDevices) while there are hardware devices.
EglDeviceSelection selectEglDevice(const EglDeviceEnvironment& environment, int hardwareDevices);

} // namespace sl
