// Lesson: percentage-closer filtering's fixed kernel (Reeves, Salesin & Cook 1987) against the true penumbra of an
// area light, which widens with the distance between caster and receiver; PCSS (Fernando 2005) sizes its kernel per
// pixel.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

#include <algorithm>

namespace sl
{

Lesson pcfFixedKernelLesson()
{
  Lesson lesson{ "pcf-fixed-kernel", "PCF's fixed kernel against a true penumbra",
    "A real penumbra is sharp where the caster touches the receiver and widens with distance; what "
    "does a filter of one fixed width get wrong, and where?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`contact`: a 0.5 x 1 x 0.5 box standing on the ground under a 0.8 x 0.8 area light off to the side. The "
      "exact penumbra is zero wide at the box's foot and widens towards the far end of the shadow (contact "
      "hardening). PCF averages the shadow test over a kernel of `kernel_texels` texels, the same everywhere; PCSS "
      "first searches for blockers and sizes the kernel from the light's size and the blocker's distance. The truth "
      "is the ray-traced visible fraction of the light. A wide kernel compares one receiver depth against texels up "
      "to its radius away; on ground lit from the side those texels hold deeper ground, so the slope bias must grow "
      "with the radius or the lit ground shadows itself: `pcf-15` (radius 7 texels) uses `bias_slope_texels=8`. "
      "(PCSS compares each tap against the receiver's tangent plane instead, `receiver_plane_bias`.) All three use "
      "one 2048-texel map, so that a texel means the same on the ground for each.");
    lesson.reference("reference", "contact");
    lesson.render({ "pcf-3", "contact", "pcf", { "kernel_texels=3", "shadow_map_size=2048" }, {}, "reference" });
    lesson.render(
      { "pcf-15", "contact", "pcf", { "kernel_texels=15", "bias_slope_texels=8", "shadow_map_size=2048" }, {}, "reference" });
    lesson.render({ "pcss", "contact", "pcss", { "shadow_map_size=2048" }, {}, "reference" });

    lesson.montage("visibility", "**Visibility** (1 = lit): the reference, two fixed kernels, and PCSS.",
      { "reference", "pcf-3", "pcf-15", "pcss" }, "visibility");
    lesson.errorMontage("error", "**Error against the reference** (blue = too dark, red = too bright). A kernel "
      "narrower than the true penumbra leaves it too hard (blue and red bands side by side), a wider one blurs a "
      "sharp edge.", { "pcf-3", "pcf-15", "pcss" });
    lesson.probe("probe", "**The narrow kernel's worst pixel, inside:** the taps it read and compared, against the "
      "extent of the light the receiver sees.", "pcf-3", LessonPixel::largestError());

    lesson.measure("largest kernel (texels)", "pcf-3", "/buffers/kernel_texels/max");
    lesson.measure("largest kernel (texels)", "pcf-15", "/buffers/kernel_texels/max");
    lesson.measure("largest penumbra kernel (texels)", "pcss", "/buffers/penumbra_kernel_texels/max");
    lesson.measure("mean penumbra kernel (texels)", "pcss", "/buffers/penumbra_kernel_texels/mean");
    lesson.measure("penumbra pixels (0 < reference < 1)", "pcf-3", "/error/penumbra/pixels");
    for (const char* run : { "pcf-3", "pcf-15", "pcss" })
    {
      lesson.measure("RMSE over the penumbra", run, "/error/penumbra/rmse");
      lesson.measure("RMSE over every covered pixel", run, "/error/covered/rmse");
      lesson.measure("share of pixels wrong by more than 0.05", run, "/error/covered/fraction_above_0.05");
    }

    const auto penumbra = [&](const char* run) { return lesson.value(run, "/error/penumbra/rmse"); };
    lesson.observation(lesson.value("pcss", "/buffers/penumbra_kernel_texels/max") > lesson.value("pcf-15", "/buffers/kernel_texels/max")
        ? "PCF's kernel is never wider than its setting; PCSS's grows far past the wider fixed kernel where the "
          "penumbra is widest, and shrinks towards the box's foot."
        : "PCSS's widest kernel is no wider than the wider fixed kernel here.");
    lesson.observation(penumbra("pcss") < std::min(penumbra("pcf-3"), penumbra("pcf-15"))
        ? "PCSS has the smallest penumbra error of the three: a kernel sized per pixel follows the widening penumbra "
          "that no single width fits."
        : "PCSS does not have the smallest penumbra error of the three here: its blocker search averages what it "
          "finds (see the PCSS lesson).");
    const auto covered = [&](const char* run) { return lesson.value(run, "/error/covered/rmse"); };
    lesson.observation(penumbra("pcf-15") < penumbra("pcf-3")
        ? "Over the penumbra, the wider fixed kernel errs less than the narrow one: most of this penumbra is wider than "
          "3 texels. Neither width fits both ends of it."
        : "Over the penumbra, the narrow fixed kernel errs less than the wide one: most of this penumbra is narrow. "
          "Neither width fits both ends of it.");
    lesson.observation(covered("pcf-15") > covered("pcf-3")
        ? "Over every covered pixel the wide kernel errs more than the narrow one: it also blurs the edges of the "
          "box's own faces and the lit ground near the shadow, where the truth is sharp."
        : "Over every covered pixel the wide kernel errs no more than the narrow one.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sweep the kernel and find the width with the least error, for this scene only:",
      "shadowlab bench datasets/contact/scene.json -t pcf --sweep kernel_texels=1,3,7,15,31 -r " + resolution +
        " --repeat 1 --reference-samples 64 --out out/pcf-kernels");
    lesson.tryNext("Grow the light: the true penumbra widens, PCF's does not:",
      "shadowlab render datasets/contact/scene.json -t pcf --set kernel_texels=15 --scene-set /lights/0/size=2 -r " +
        resolution + " --out out/pcf-big-light");
    lesson.tryNext("Compare a run with the reference yourself (error.png, metrics.json):",
      lesson.renderCommand("reference", "out/reference") + " && " + lesson.renderCommand("pcf-15", "out/pcf-15") +
        " && shadowlab compare out/pcf-15/buffers.vti out/reference/buffers.vti --out out/pcf-15-error");
  };
  return lesson;
}

} // namespace sl
