// Lesson: z-partitioning (Scherzer et al. 2011 §4.3.1: cascaded / parallel-split shadow maps) against one uniform map
// and LiSPSM (§4.2) of the same total texels, on the deep view with the light overhead and behind the viewer (Fig. 14-15),
// measured by the sampling-error buffers binned over the eye's depth (metrics/DepthProfile.h) and by the hard shadow's
// error against exact shadow volumes.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

#include <string>
#include <vector>

namespace sl
{

namespace
{

// One map of the comparison, on one dataset; every map holds 256^2 texels in all.
struct CascadeLessonRun
{
  std::string name;
  std::string dataset;
  std::vector<std::string> settings;
};

constexpr int kCascadeLessonBins = 6;

} // namespace

Lesson cascadedShadowMapsLesson()
{
  Lesson lesson{ "cascaded-shadow-maps",
    "Cascaded shadow maps: uniform, LiSPSM and 4 cascades on one scale of texel_ratio_t",
    "One shadow map spreads its texels evenly over everything the eye sees, from the eye's feet to the horizon. "
    "What do four maps, each focused on one slice of the eye's depth, buy over one map of the same texels, and over "
    "LiSPSM's warp, with the light overhead and with the light behind the viewer?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`deep-view`: a long ground seen from eye height, posts and buildings at growing distances, a directional light "
      "from overhead, perpendicular to the view; `deep-view-behind`: the same view with the light 15 degrees off the "
      "view direction, from behind the viewer (the survey's Fig. 14-15 case). *Z-partitioning* (Scherzer et al. "
      "2011, §4.3.1; cascaded or parallel-split shadow maps) cuts the eye's depth range [z_n, z_f] of the visible "
      "receivers at C_i = z_n (z_f / z_n)^(i/m) (the log split) and gives each slice its own map focused on the "
      "receivers it owns; each pixel reads the map of its slice (buffer `cascade`, the survey's Fig. 15 colour "
      "coding). Every run here spends the same 256^2 texels: one 256^2 map, uniform or LiSPSM-warped (§4.2), "
      "against 4 cascades of 128^2. `texel_ratio_t` is the survey's aliasing error m along the map's t axis "
      "(screen pixels one texel step spans; above 1: undersampled); an unwarped map (the uniform one, each cascade) "
      "orients its t axis by the light alone, LiSPSM along the view, so `texel_ratio`, the most stretched direction, "
      "compares them axis for axis. The truth is the exact hard shadow from stencil shadow volumes.");
    const std::vector<CascadeLessonRun> runs = {
      { "uniform", "deep-view", { "shadow_map_size=256" } },
      { "lispsm", "deep-view", { "shadow_map_size=256", "warp=lispsm" } },
      { "cascades", "deep-view", { "shadow_map_size=128", "cascades=4" } },
      { "uniform-behind", "deep-view-behind", { "shadow_map_size=256" } },
      { "lispsm-behind", "deep-view-behind", { "shadow_map_size=256", "warp=lispsm" } },
      { "cascades-behind", "deep-view-behind", { "shadow_map_size=128", "cascades=4" } },
    };
    lesson.render({ "exact", "deep-view", "shadow-volume", {}, {}, "" });
    lesson.render({ "exact-behind", "deep-view-behind", "shadow-volume", {}, {}, "" });
    for (const CascadeLessonRun& run : runs)
    {
      LessonRunSpec spec{ run.name, run.dataset, "hard", run.settings, {},
        run.dataset == "deep-view" ? "exact" : "exact-behind" };
      spec.depthProfiles = { "texel_ratio_t", "texel_ratio" };
      spec.depthBins = kCascadeLessonBins;
      lesson.render(spec);
    }
    const std::vector<std::string> overhead = { "uniform", "lispsm", "cascades" };
    const std::vector<std::string> behind = { "uniform-behind", "lispsm-behind", "cascades-behind" };

    lesson.montage("texel_ratio_t", "**texel_ratio_t on one scale, light overhead** (pixels per texel along each "
      "map's t axis). Bright = one texel spread over many pixels.", overhead, "texel_ratio_t");
    lesson.montage("texel_ratio_t_behind", "**texel_ratio_t on one scale, light behind the viewer.**", behind,
      "texel_ratio_t");
    lesson.montage("texel_ratio", "**texel_ratio (the most stretched direction) on one scale, both lights:** "
      "the axis-free comparison.", { "uniform", "lispsm", "cascades", "uniform-behind", "lispsm-behind",
      "cascades-behind" }, "texel_ratio");
    lesson.montage("cascade", "**Which map each pixel reads** (buffer `cascade`), light overhead and behind: the "
      "four slices of the log split.", { "cascades", "cascades-behind" }, "cascade");
    lesson.errorMontage("error", "**Against the exact hard shadow** (blue = too dark, red = too bright), light "
      "overhead then behind.", { "uniform", "lispsm", "cascades", "uniform-behind", "lispsm-behind",
      "cascades-behind" });
    lesson.probe("probe", "**One pixel of the cascaded run, inside:** the map of the pixel's own cascade, the texel "
      "it reads and, outlined, the pixel's footprint there; the panel names the cascade and its split depths.",
      "cascades", LessonPixel::largestValue("texel_ratio_t"));

    const std::string last = std::to_string(kCascadeLessonBins - 1);
    const std::string nearest = "/depth_profile/texel_ratio/bins/0/median";
    const std::string farthest = "/depth_profile/texel_ratio/bins/" + last + "/median";
    const std::string nearestT = "/depth_profile/texel_ratio_t/bins/0/median";
    const std::string farthestT = "/depth_profile/texel_ratio_t/bins/" + last + "/median";
    for (const std::vector<std::string>* set : { &overhead, &behind })
    {
      for (const std::string& run : *set)
      {
        lesson.measure("median texel_ratio_t, nearest sixth of the depths", run, nearestT);
        lesson.measure("median texel_ratio_t, farthest sixth of the depths", run, farthestT);
        lesson.measure("median texel_ratio, nearest sixth of the depths", run, nearest);
        lesson.measure("median texel_ratio, farthest sixth of the depths", run, farthest);
        lesson.measure("share of pixels wrong by more than 0.05", run, "/error/covered/fraction_above_0.05");
      }
    }
    for (const char* run : { "lispsm", "lispsm-behind" })
    {
      lesson.measure("the warp's n (world units)", run, "/light_view/warp/n");
    }
    for (int k = 0; k <= 4; ++k)
    {
      lesson.measure("split depth C_" + std::to_string(k) + " (eye depth)", "cascades",
        k < 4 ? "/light_view/cascades/" + std::to_string(k) + "/near" : "/light_view/cascades/3/far");
    }

    const auto value = [&](const std::string& run, const std::string& pointer) { return lesson.value(run, pointer); };
    const auto wrong = [&](const std::string& run) { return value(run, "/error/covered/fraction_above_0.05"); };
    lesson.observation(value("cascades", nearest) < 0.5 * value("uniform", nearest)
        ? "Light overhead: on the nearest ground the cascades' texels span less than half the screen pixels the "
          "uniform map's do: the first cascade's 128^2 texels cover only the first slice, a few metres of ground."
        : "Light overhead: the cascades do not halve the nearest ground's texel_ratio against the uniform map here.");
    lesson.observation(value("cascades", farthest) > value("uniform", farthest)
        ? "What the near ground gains, the far ground pays: its texel_ratio is larger under the cascades than under "
          "the uniform map, which spent more texels there than the screen could show."
        : "The far ground's texel_ratio is not larger under the cascades than under the uniform map here.");
    lesson.observation(wrong("cascades") < wrong("uniform") && wrong("lispsm") < wrong("uniform")
        ? "Light overhead, both the warp and the cascades misclassify fewer pixels than the uniform map of the same "
          "texels."
        : "Light overhead, the warp and the cascades do not both misclassify fewer pixels than the uniform map here.");
    lesson.observation(value("lispsm-behind", "/light_view/warp/n") > 2.0 * value("lispsm", "/light_view/warp/n")
        ? "With the light behind the viewer the angle gamma between view and light is small and LiSPSM's n grows as "
          "n_opt / sin(gamma): the warp fades toward the uniform map (§4.2.2)."
        : "LiSPSM's n does not grow more than twofold with the light behind the viewer here.");
    lesson.observation(value("cascades-behind", nearest) < 0.5 * value("lispsm-behind", nearest) &&
          wrong("cascades-behind") < wrong("lispsm-behind")
        ? "Light behind: the cascades still halve the nearest ground's texel_ratio against LiSPSM and misclassify "
          "fewer pixels than it: a slice's map is small because its slice is, whatever the light's direction "
          "(Fig. 14-15), where a warp along the view needs the light across it."
        : "Light behind: the cascades do not both halve the nearest ground's texel_ratio against LiSPSM and "
          "misclassify fewer pixels than it here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Write the cascaded run with its buffers: `cascade`, the sampling-error buffers of each pixel's "
                   "own cascade, and every cascade's map in light_space.vti (shadow_map_depth_c0 .. _c3):",
      lesson.renderCommand("cascades", "out/cascades"));
    lesson.tryNext("Warp each cascade too (§4.4: the two combine; Fig. 17):",
      "shadowlab render datasets/deep-view/scene.json -t hard --set shadow_map_size=128 --set cascades=4 --set "
      "warp=lispsm -r " + resolution + " --out out/cascades-lispsm");
    lesson.tryNext("The survey's Fig. 18 as a bench: the error over the view against the number of maps at equal "
                   "total texels, warping, z-partitioning and both:",
      "shadowlab bench datasets/deep-view/scene.json datasets/deep-view-behind/scene.json -t hard --sweep "
      "'cascades+shadow_map_size=1+512,4+256' --sweep 'warp+warp_n=lispsm+1e6,lispsm+0' --view-stats "
      "texel_ratio -r 128x64 --repeat 1 --reference-samples 1 --out out/fig18");
  };
  return lesson;
}

} // namespace sl
