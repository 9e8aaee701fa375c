// Lesson: perspective and projection aliasing, measured by hard's texel_ratio (the aliasing error m of the survey's
// Eq. 2, Scherzer et al. 2011 §4: screen pixels spanned by one shadow-map texel along its most stretched direction).
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson perspectiveAliasingLesson()
{
  Lesson lesson{ "perspective-aliasing", "Perspective and projection aliasing: texel_ratio on a grazing receiver",
    "Why do hard shadow edges turn into stair steps where the light grazes the receiver, and "
    "what does a larger shadow map buy there?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "A shadow map samples the scene on a regular grid in the light's view; the camera sees that grid stretched. "
      "`texel_ratio` is the survey's aliasing error m (Scherzer et al. 2011, Eq. 2): how many screen pixels one "
      "shadow-map texel spans along its most stretched direction. Above 1, several pixels share one depth sample "
      "and shadow edges show the texel grid. Two causes multiply: *perspective aliasing* (the camera magnifies what "
      "is near it) and *projection aliasing* (a receiver nearly parallel to the light's rays, as the ground of "
      "`grazing`, where the light stands about 80 degrees from the ground's normal, is covered by few texels). "
      "`planar-occluder` lights its ground from straight above and is the control.");
    lesson.render({ "overhead-512", "planar-occluder", "hard", { "shadow_map_size=512" }, {}, "" });
    lesson.render({ "grazing-512", "grazing", "hard", { "shadow_map_size=512" }, {}, "" });
    lesson.render({ "grazing-2048", "grazing", "hard", { "shadow_map_size=2048" }, {}, "" });

    lesson.montage("texel_ratio", "**texel_ratio on one scale.** Overhead light against grazing light at the same "
      "map size, then the grazing light with a map four times wider. Bright = one texel spread over many pixels.",
      { "overhead-512", "grazing-512", "grazing-2048" }, "texel_ratio");
    lesson.montage("visibility", "**What it looks like.** The hard shadows of the same runs (1 = lit).",
      { "overhead-512", "grazing-512", "grazing-2048" }, "visibility");
    lesson.probe("probe", "**One pixel, inside.** The texel it reads, the light's rays through the receiver, and "
      "the ratio the figure's legend lists as `texel_ratio`.", "grazing-512", LessonPixel::largestValue("texel_ratio"));

    for (const char* run : { "overhead-512", "grazing-512", "grazing-2048" })
    {
      lesson.measure("shadow-map texels per side", run, "/light_view/resolution");
      lesson.measure("mean texel_ratio (pixels per texel)", run, "/buffers/texel_ratio/mean");
      lesson.measure("largest texel_ratio", run, "/buffers/texel_ratio/max");
    }

    const double overhead = lesson.value("overhead-512", "/buffers/texel_ratio/mean");
    const double grazing = lesson.value("grazing-512", "/buffers/texel_ratio/mean");
    const double grazingWide = lesson.value("grazing-2048", "/buffers/texel_ratio/mean");
    lesson.observation(grazing > overhead
        ? "At the same map size, the grazing light's texels cover more pixels on average than the overhead light's: "
          "projection aliasing, which no change of the camera removes."
        : "At the same map size, the grazing light's texels do not cover more pixels on average than the overhead "
          "light's here: the camera's framing dominates.");
    lesson.observation(lesson.value("grazing-512", "/buffers/texel_ratio/max") > 1.0
        ? "On the grazing ground the 512-texel map is undersampled (largest ratio above 1): neighbouring pixels read "
          "the same texel, and a shadow edge crossing them moves in steps a texel wide."
        : "Even on the grazing ground the 512-texel map is not undersampled at this image size.");
    lesson.observation(grazing / grazingWide > 3.0 && grazing / grazingWide < 5.0
        ? "A map four times wider divides the mean ratio by about four: resolution buys the detail back, at sixteen "
          "times the texels. The ratio stays largest where the ground runs most nearly along the light's rays and "
          "nearest the camera; warping the map's projection (PSM, LiSPSM) or splitting it (cascades) spends texels "
          "there instead of everywhere."
        : "A map four times wider does not divide the mean ratio by about four here: the light frustum's focus on "
          "the visible receivers changes with the map.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Write both grazing runs with their buffers and put texel_ratio side by side yourself:",
      lesson.renderCommand("grazing-512", "out/grazing-512") + " && " + lesson.renderCommand("grazing-2048", "out/grazing-2048") +
        " && shadowlab montage out/grazing-512 out/grazing-2048 --buffer texel_ratio --out texel_ratio.png");
    lesson.tryNext("Raise the light towards the zenith and watch the ratio fall (the light's normal must keep facing "
                   "the scene):",
      "shadowlab render datasets/grazing/scene.json -t hard --scene-set '/lights/0/center=[2,4,0]' --scene-set "
      "'/lights/0/normal=[-2,-4,0]' -r " + resolution + " --out out/higher-light");
    lesson.tryNext("Filtering hides the stair steps but not the lost detail; compare PCF's kernel on the same map:",
      "shadowlab render datasets/grazing/scene.json -t pcf --set shadow_map_size=512 --set kernel_texels=5 -r " +
        resolution + " --out out/grazing-pcf");
  };
  return lesson;
}

} // namespace sl
