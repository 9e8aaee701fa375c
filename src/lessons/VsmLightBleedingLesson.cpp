// Lesson: variance shadow maps' light bleeding (Donnelly & Lauritzen 2006; Lauritzen 2007): Chebyshev's bound p_max
// from the filtered moments is only an upper bound of the filtered shadow test, loose where the filter region holds
// depths far apart; light-bleeding reduction trades the leak for darkening.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

#include <cmath>
#include <string>

namespace sl
{

namespace
{
constexpr int boxTexels = 21;
}

Lesson vsmLightBleedingLesson()
{
  Lesson lesson{ "vsm-light-bleeding", "VSM light bleeding: light_leak and its reduction",
    "Why does a variance shadow map let light into a shadow where two occluders overlap, and what does "
    "light-bleeding reduction cost?" };
  lesson.build = [](LessonBuilder& lesson) {
    // A box wide enough that the halo where the shadows overlap spans several pixels of the page's figures (at 5
    // texels it is one or two); tests/cli/LessonClaimsTest.cpp asserts its size.
    const std::string box = std::to_string(boxTexels);
    const std::string pcf = "pcf-" + box;
    lesson.sceneNote(
      "VSM stores depth and squared depth, blurs them, and bounds the fraction of the blurred region closer to the "
      "light than the receiver by Chebyshev's inequality, p_max = s^2 / (s^2 + (t - mu)^2). It is exact for one "
      "occluder over one receiver; where the region holds two occluders at different depths over the receiver "
      "(`stacked-occluders`, squares at heights 0.6 and 1.5), the variance is large and p_max lets light through "
      "the lower occluder's shadow, in a halo along the upper occluder's shadow edge. `light_leak` is p_max minus "
      "PCF over the same box of texels, compared as `pcf` compares (with its default bias). Light-bleeding "
      "reduction (`light_bleeding_reduction` = a) maps [a, 1] of p_max onto [0, 1] and sets less than a to 0. The "
      "truth here is `pcf` over the same " + box + "-texel box (`kernel_texels=" + box + "`, VSM's "
      "`prefilter_texels=" + box + "`), on the same 1024-texel map, so what remains is the bound's own error.");
    lesson.render({ pcf, "stacked-occluders", "pcf", { "shadow_map_size=1024", "kernel_texels=" + box }, {}, "" });
    for (const char* amount : { "0", "0.2", "0.5" })
    {
      lesson.render({ std::string("vsm-") + amount, "stacked-occluders", "vsm",
        { "shadow_map_size=1024", "prefilter_texels=" + box, std::string("light_bleeding_reduction=") + amount }, {}, pcf });
    }

    lesson.montage("light_leak", "**light_leak** (p_max minus PCF over the same texels; white = none, red = light "
      "let through) without reduction: the halo along the upper occluder's shadow edge, inside the lower one's.",
      { "vsm-0" }, "light_leak");
    lesson.errorMontage("error", "**Visibility against PCF over the same box** (red = too bright: bleeding; blue = "
      "too dark: what the reduction costs), for reductions 0, 0.2 and 0.5.", { "vsm-0", "vsm-0.2", "vsm-0.5" });
    lesson.probe("probe", "**The pixel that bleeds most, inside:** the moments of its box, Chebyshev's bound and "
      "the true filtered test over the same texels.", "vsm-0", LessonPixel::largestValue("light_leak"));

    lesson.measure("largest light_leak", "vsm-0", "/buffers/light_leak/max");
    lesson.measure("mean light_leak", "vsm-0", "/buffers/light_leak/mean");
    lesson.measure("largest error against PCF", "vsm-0", "/error/covered/max_abs_error");
    lesson.measure("mean visibility", pcf, "/buffers/visibility/mean");
    for (const char* run : { "vsm-0", "vsm-0.2", "vsm-0.5" })
    {
      lesson.measure("mean visibility", run, "/buffers/visibility/mean");
      lesson.measure("share of pixels off PCF by more than 0.05", run, "/error/covered/fraction_above_0.05");
      lesson.measure("RMSE against PCF", run, "/error/covered/rmse");
    }

    lesson.observation(lesson.value("vsm-0", "/buffers/light_leak/max") > 0.05
        ? "Without reduction, p_max exceeds PCF over the same texels by more than 0.05 in the halo along the upper "
          "occluder's shadow edge: that is light bleeding."
        : "Without reduction, p_max stays within 0.05 of PCF over the same texels everywhere here.");
    lesson.observation(std::abs(lesson.value("vsm-0", "/error/covered/max_abs_error") -
                         lesson.value("vsm-0", "/buffers/light_leak/max")) < 1e-3
        ? "The unreduced run's largest error against the `pcf` run is its largest light_leak: the two read the same "
          "texels of the same map, so that error is the bleeding alone."
        : "The unreduced run's largest error against the `pcf` run is not its largest light_leak here.");
    lesson.observation(lesson.value("vsm-0.5", "/buffers/visibility/mean") < lesson.value("vsm-0", "/buffers/visibility/mean")
        ? "Reduction only ever lowers visibility: the mean falls as the amount grows, removing the leak and darkening "
          "the true penumbra with it."
        : "Reduction did not lower the mean visibility here.");

    lesson.observation(lesson.value("vsm-0.5", "/error/covered/rmse") > lesson.value("vsm-0.2", "/error/covered/rmse") &&
          lesson.value("vsm-0.2", "/error/covered/rmse") > lesson.value("vsm-0", "/error/covered/rmse")
        ? "Against PCF, the reduction costs more than it saves in this scene: the RMSE grows with the amount, because "
          "the darkening reaches every penumbra pixel while the bleeding is confined to where the occluders overlap."
        : "Against PCF, the RMSE does not grow steadily with the amount of reduction in this scene.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sweep the reduction against the ray-traced reference:",
      "shadowlab bench datasets/stacked-occluders/scene.json -t vsm --sweep light_bleeding_reduction=0,0.1,0.2,0.4,0.6 -r " +
        resolution + " --repeat 1 --reference-samples 64 --out out/vsm-reduction");
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
