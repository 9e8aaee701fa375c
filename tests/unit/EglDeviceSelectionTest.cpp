// The EGL device a process renders on, from its batch system's GPU assignment (gl/EglDeviceSelection.h): a pure
// function, tested without a GPU.
#include "core/Error.h"
#include "gl/EglDeviceSelection.h"

#include <gtest/gtest.h>

namespace sl
{
namespace
{

TEST(EglDeviceSelection, TheExplicitOverrideWinsAndIsChecked)
{
  EglDeviceEnvironment environment;
  environment.explicitDevice = "2";
  environment.slurmStepGpus = "1";
  const EglDeviceSelection chosen = selectEglDevice(environment, 4);
  EXPECT_EQ(chosen.index, 2);
  EXPECT_TRUE(chosen.assigned);
  EXPECT_EQ(chosen.source, "SHADOWLAB_EGL_DEVICE=2");
  for (const char* bad : { "4", "-1", "one", "1,2" })
  {
    environment.explicitDevice = bad;
    try
    {
      selectEglDevice(environment, 4);
      ADD_FAILURE() << bad << " accepted";
    }
    catch (const GraphicsError& error)
    {
      EXPECT_NE(std::string(error.what()).find(std::string("SHADOWLAB_EGL_DEVICE=") + bad), std::string::npos)
        << error.what();
    }
  }
  // No hardware device (llvmpipe): nothing to check it against; the surfaceless display is used and named.
  environment.explicitDevice = "7";
  EXPECT_EQ(selectEglDevice(environment, 0).index, 7);
}

TEST(EglDeviceSelection, SlurmsAssignmentInItsOrderOfPrecedence)
{
  EglDeviceEnvironment environment;
  environment.cudaVisibleDevices = "3";
  EXPECT_EQ(selectEglDevice(environment, 4).index, 3);
  EXPECT_EQ(selectEglDevice(environment, 4).source, "CUDA_VISIBLE_DEVICES=3");
  environment.slurmJobGpus = "2,3";
  EXPECT_EQ(selectEglDevice(environment, 4).index, 2);
  environment.slurmStepGpus = "1";
  const EglDeviceSelection step = selectEglDevice(environment, 4);
  EXPECT_EQ(step.index, 1);
  EXPECT_EQ(step.source, "SLURM_STEP_GPUS=1");
  EXPECT_TRUE(step.assigned);
}

TEST(EglDeviceSelection, HiddenDevicesUuidsAndNoAssignment)
{
  EglDeviceEnvironment environment;
  // The job's cgroup shows EGL only its GPU 5: the one device listed is it.
  environment.slurmStepGpus = "5";
  const EglDeviceSelection hidden = selectEglDevice(environment, 1);
  EXPECT_EQ(hidden.index, 0);
  EXPECT_NE(hidden.source.find("EGL lists 1 device(s)"), std::string::npos) << hidden.source;
  environment = {};
  environment.cudaVisibleDevices = "GPU-8e1f2c3a-0000-1111-2222-333344445555";
  const EglDeviceSelection uuid = selectEglDevice(environment, 2);
  EXPECT_EQ(uuid.index, 0);
  EXPECT_NE(uuid.source.find("not an index"), std::string::npos) << uuid.source;
  const EglDeviceSelection none = selectEglDevice({}, 2);
  EXPECT_EQ(none.index, 0);
  EXPECT_FALSE(none.assigned);
}

} // namespace
} // namespace sl
