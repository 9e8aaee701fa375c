// Lesson: PCSS's blocker search and its planar assumption (Fernando 2005; as VSSM, Yang et al. 2010, §1 puts it):
// the blockers found in the search kernel are replaced by one plane at their average depth, which is exact for one
// planar occluder parallel to the light and wrong where blockers at several depths overlap.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson pcssBlockerSearchLesson()
{
  Lesson lesson{ "pcss-blocker-search", "PCSS's blocker search and its planar assumption",
    "PCSS estimates a penumbra from the average depth of the blockers it finds; when is that average "
    "the right blocker, and what happens when two occluders at different heights overlap?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "PCSS in three steps: search the shadow map over a kernel w_i (sized from the light and the receiver's depth) "
      "for texels closer to the light than the receiver and average their depths (`avg_blocker_depth`); estimate "
      "the penumbra width w_light (d - z_avg) / z_avg (`penumbra_width`, similar triangles between light, "
      "blocker and receiver); filter with PCF over that width. The similar triangles assume one blocker plane "
      "parallel to the light. `planar-occluder` is exactly that (one square above the ground); `stacked-occluders` "
      "has two squares at heights 0.6 and 1.5 whose penumbrae overlap, so one average depth stands for two.");
    lesson.reference("reference-planar", "planar-occluder");
    lesson.render({ "pcss-planar", "planar-occluder", "pcss", {}, {}, "reference-planar" });
    lesson.reference("reference-stacked", "stacked-occluders");
    lesson.render({ "pcss-stacked", "stacked-occluders", "pcss", {}, {}, "reference-stacked" });

    lesson.montage("penumbra_width", "**The estimated penumbra width**, on one scale for both scenes.",
      { "pcss-planar", "pcss-stacked" }, "penumbra_width");
    lesson.montage("visibility", "**Visibility** (1 = lit): the stacked occluders, reference and PCSS.",
      { "reference-stacked", "pcss-stacked" }, "visibility");
    lesson.errorMontage("error", "**Error against each scene's reference** (blue = too dark, red = too bright).",
      { "pcss-planar", "pcss-stacked" });
    lesson.probe("probe", "**The stacked run's worst pixel, inside:** the blocker search kernel, the blockers it "
      "found, their average depth, and the penumbra kernel sized from it.", "pcss-stacked",
      LessonPixel::largestError());

    for (const char* run : { "pcss-planar", "pcss-stacked" })
    {
      lesson.measure("mean blocker search kernel (texels)", run, "/buffers/blocker_kernel_texels/mean");
      lesson.measure("largest estimated penumbra width (world units)", run, "/buffers/penumbra_width/max");
      lesson.measure("penumbra pixels (0 < reference < 1)", run, "/error/penumbra/pixels");
      lesson.measure("RMSE over the penumbra", run, "/error/penumbra/rmse");
      lesson.measure("largest error", run, "/error/covered/max_abs_error");
    }

    lesson.observation(lesson.value("pcss-stacked", "/error/penumbra/rmse") > lesson.value("pcss-planar", "/error/penumbra/rmse")
        ? "The penumbra error is larger on the stacked occluders than on the single plane: where two blockers overlap, "
          "their average depth is neither, and the penumbra drawn from it is too wide for the lower one and too "
          "narrow for the upper one."
        : "The penumbra error is not larger on the stacked occluders than on the single plane here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("VSSM splits the kernels into sub-kernels to meet the same problem; put both on the stacked "
                   "occluders:",
      "shadowlab bench datasets/stacked-occluders/scene.json -t pcss,vssm -r " + resolution +
        " --repeat 1 --reference-samples 64 --out out/pcss-vs-vssm");
    lesson.tryNext("Move the upper occluder and watch the error follow the overlap:",
      "shadowlab render datasets/stacked-occluders/scene.json -t pcss --scene-set '/objects/2/center=[0.3,2.2,0.3]' -r " +
        resolution + " --out out/pcss-moved");
    lesson.tryNext("Write the stacked run with its buffers to look at avg_blocker_depth and blocker_samples:",
      lesson.renderCommand("pcss-stacked", "out/pcss-stacked"));
  };
  return lesson;
}

} // namespace sl
