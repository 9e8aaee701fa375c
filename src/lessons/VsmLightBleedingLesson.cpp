// Lesson: variance shadow maps' light bleeding (Donnelly & Lauritzen 2006; Lauritzen 2007): Chebyshev's bound p_max
// from the filtered moments is only an upper bound of the filtered shadow test, loose where the filter region holds
// depths far apart; light-bleeding reduction trades the leak for darkening.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson vsmLightBleedingLesson()
{
  Lesson lesson;
  lesson.name = "vsm-light-bleeding";
  lesson.title = "VSM light bleeding: light_leak and its reduction";
  lesson.question = "Why does a variance shadow map let light into a shadow where two occluders overlap, and what does "
                    "light-bleeding reduction cost?";
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "VSM stores depth and squared depth, blurs them, and bounds the fraction of the blurred region closer to the "
      "light than the receiver by Chebyshev's inequality, p_max = s^2 / (s^2 + (t - mu)^2). It is exact for one "
      "occluder over one receiver; where the region holds two occluders at different depths over the receiver "
      "(`stacked-occluders`, squares at heights 0.6 and 1.5), the variance is large and p_max lets light through "
      "the lower occluder's shadow. `light_leak` is p_max minus the true PCF over the same box of texels. "
      "Light-bleeding reduction (`light_bleeding_reduction` = a) maps [a, 1] of p_max onto [0, 1] and sets less "
      "than a to 0. The truth here is PCF over the same 5-texel box (`kernel_texels=5`, VSM's `prefilter_texels` "
      "is 5), on the same 1024-texel map, so what remains is the bound's own error.");
    lesson.render({ "pcf-5", "stacked-occluders", "pcf", { "shadow_map_size=1024", "kernel_texels=5" }, {}, "" });
    lesson.render({ "vsm-0", "stacked-occluders", "vsm", { "shadow_map_size=1024", "light_bleeding_reduction=0" }, {}, "pcf-5" });
    lesson.render({ "vsm-0.2", "stacked-occluders", "vsm", { "shadow_map_size=1024", "light_bleeding_reduction=0.2" }, {}, "pcf-5" });
    lesson.render({ "vsm-0.5", "stacked-occluders", "vsm", { "shadow_map_size=1024", "light_bleeding_reduction=0.5" }, {}, "pcf-5" });

    lesson.montage("light_leak", "**light_leak** (p_max minus the true PCF; white = none, red = light let through) "
      "without reduction.", { "vsm-0" }, "light_leak");
    lesson.errorMontage("error", "**Visibility against PCF over the same box** (red = too bright: bleeding; blue = "
      "too dark: what the reduction costs), for reductions 0, 0.2 and 0.5.", { "vsm-0", "vsm-0.2", "vsm-0.5" });
    lesson.probe("probe", "**The pixel that bleeds most, inside:** the moments of its box, Chebyshev's bound and "
      "the true filtered test over the same texels.", "vsm-0", LessonPixel::largestValue("light_leak"));

    lesson.measure("largest light_leak", "vsm-0", "/buffers/light_leak/max");
    lesson.measure("mean light_leak", "vsm-0", "/buffers/light_leak/mean");
    lesson.measure("mean visibility", "pcf-5", "/buffers/visibility/mean");
    for (const char* run : { "vsm-0", "vsm-0.2", "vsm-0.5" })
    {
      lesson.measure("mean visibility", run, "/buffers/visibility/mean");
      lesson.measure("share of pixels off PCF by more than 0.05", run, "/error/covered/fraction_above_0.05");
      lesson.measure("RMSE against PCF", run, "/error/covered/rmse");
    }

    lesson.observation(lesson.value("vsm-0", "/buffers/light_leak/max") > 0.05
        ? "Without reduction, p_max exceeds the true filtered test by more than 0.05 somewhere: that is light bleeding."
        : "Without reduction, p_max stays within 0.05 of the true filtered test everywhere here.");
    lesson.observation(lesson.value("vsm-0.5", "/buffers/visibility/mean") < lesson.value("vsm-0", "/buffers/visibility/mean")
        ? "Reduction only ever lowers visibility: the mean falls as the amount grows, removing the leak and darkening "
          "the true penumbra with it."
        : "Reduction did not lower the mean visibility here.");

    lesson.observation(lesson.value("vsm-0.5", "/error/covered/rmse") > lesson.value("vsm-0", "/error/covered/rmse")
        ? "Against PCF, the reduction costs more than it saves in this scene: the RMSE grows with the amount, because "
          "the darkening reaches every penumbra pixel while the bleeding is confined to where the occluders overlap."
        : "Against PCF, the reduction lowers the RMSE in this scene: the bleeding it removes outweighs the darkening.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sweep the reduction against the ray-traced reference:",
      "shadowlab bench datasets/stacked-occluders/scene.json -t vsm --sweep light_bleeding_reduction=0,0.1,0.2,0.4,0.6 -r " +
        resolution + " --repeat 1 --samples 64 --out out/vsm-reduction");
    lesson.tryNext("Exponential shadow maps bound the test differently and leak elsewhere (their light_leak has the "
                   "same meaning):",
      "shadowlab render datasets/stacked-occluders/scene.json -t esm --set shadow_map_size=1024 -r " + resolution +
        " --out out/esm");
    lesson.tryNext("Write the unreduced run and put its p_max and light_leak side by side with another run:",
      lesson.renderCommand("vsm-0", "out/vsm-0") + " && " + lesson.renderCommand("vsm-0.5", "out/vsm-0.5") +
        " && shadowlab montage out/vsm-0 out/vsm-0.5 --buffer visibility --out vsm-visibility.png");
  };
  return lesson;
}

} // namespace sl
