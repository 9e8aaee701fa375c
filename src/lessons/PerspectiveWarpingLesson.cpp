// Lesson: perspective warping of the shadow map (Scherzer et al. 2011 §4.2: PSM, LiSPSM), measured on the deep view
// by the per-axis aliasing error texel_ratio_t (Eq. 2 along the map's t axis) and Eq. 1's perspective factor, binned
// over the eye's depth (metrics/DepthProfile.h), and by the hard shadow's error against exact shadow volumes.
// The maps compared are one list: a partitioned map (cascades) joins it as one more entry.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

#include <string>
#include <vector>

namespace sl
{

namespace
{

// One map of the comparison (a cascaded map joins as one more: its settings, warped = false).
struct WarpingRun
{
  const char* name;
  std::vector<std::string> settings;
  bool warped; // has a perspective warp, whose n stats.json records
};

} // namespace

Lesson perspectiveWarpingLesson()
{
  Lesson lesson{ "perspective-warping", "Perspective warping: uniform, PSM and LiSPSM on one scale of texel_ratio_t",
    "A uniform shadow map undersamples the ground near the eye and wastes texels far away. How do PSM and LiSPSM "
    "move the map's texels toward the eye, and what does the ground's own slant do to the figure the survey draws?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`deep-view`: a long ground seen from eye height, posts and buildings at growing distances, and a directional "
      "light from overhead, perpendicular to the view (the survey's Fig. 12 setting). A *perspective warp* renders "
      "the shadow map through a perspective P looking along the view direction (Scherzer et al. 2011, §4.2), so "
      "that texels near the eye are small and far ones large. Its free parameter n sets how strong: PSM uses the "
      "eye's own near distance (n = z_n), LiSPSM n_opt = z_n + sqrt(z_n z_f), the value that makes Eq. 1's error "
      "(1/z)(dz/ds) equal at the nearest and farthest depth; n -> infinity is the uniform map. `texel_ratio_t` is "
      "the survey's aliasing error m along the map's t axis, the axis the warp acts on: screen pixels one texel "
      "step spans (above 1: undersampled). `perspective_factor` is Eq. 1's (1/z)(dz/ds) alone, the error a surface "
      "facing both the eye and the light would have; on the ground it is multiplied by the projection factor "
      "cos(alpha)/cos(beta), which falls with the distance (the ground turns edge-on to the eye). The uniform map "
      "(`warp=none`) orients its axes by the light alone: here its t axis runs across the view, so its "
      "`texel_ratio_t` is the error across the view direction. The truth is the exact hard shadow from stencil "
      "shadow volumes. The Fig. 12 curves themselves, on tiles that face both the eye and the light, are the "
      "bench [`docs/bench/fig12`](../../bench/fig12/README.md).");
    const std::vector<WarpingRun> maps = { { "uniform", { "shadow_map_size=512" }, false },
      { "psm", { "shadow_map_size=512", "warp=psm" }, true }, { "lispsm", { "shadow_map_size=512", "warp=lispsm" }, true } };
    lesson.render({ "exact", "deep-view", "shadow-volume", {}, {}, "" });
    std::vector<std::string> names;
    for (const WarpingRun& map : maps)
    {
      LessonRunSpec spec{ map.name, "deep-view", "hard", map.settings, {}, "exact" };
      spec.depthProfiles = { "texel_ratio_t", "perspective_factor" };
      spec.depthBins = 6;
      lesson.render(spec);
      names.push_back(map.name);
    }

    lesson.montage("texel_ratio_t", "**texel_ratio_t on one scale** (pixels per texel along the map's t axis). "
      "Bright = one texel spread over many pixels.", names, "texel_ratio_t");
    lesson.montage("perspective_factor", "**Eq. 1's perspective factor (1/z)(dz/ds)** on one scale: the part of the "
      "error a warp controls.", names, "perspective_factor");
    lesson.montage("visibility", "**What it looks like.** The hard shadows (1 = lit), each map 512 x 512.", names,
      "visibility");
    lesson.errorMontage("error", "**Against the exact hard shadow** (blue = too dark, red = too bright): the "
      "stair-stepped edges of undersampled texels.", names);
    lesson.probe("probe", "**One pixel of the LiSPSM run, inside:** the texel it reads and, outlined in the map, the "
      "pixel's own footprint there (its four corners projected through the warp).", "lispsm",
      LessonPixel::largestValue("texel_ratio_t"));

    const std::string nearest = "/depth_profile/texel_ratio_t/bins/0/median";
    const std::string farthest = "/depth_profile/texel_ratio_t/bins/5/median";
    const std::string nearestPerspective = "/depth_profile/perspective_factor/bins/0/median";
    const std::string farthestPerspective = "/depth_profile/perspective_factor/bins/5/median";
    for (const WarpingRun& map : maps)
    {
      if (map.warped)
      {
        lesson.measure("the warp's n (world units)", map.name, "/light_view/warp/n");
      }
      lesson.measure("median texel_ratio_t, nearest sixth of the depths", map.name, nearest);
      lesson.measure("median texel_ratio_t, farthest sixth of the depths", map.name, farthest);
      lesson.measure("median perspective_factor, nearest sixth", map.name, nearestPerspective);
      lesson.measure("median perspective_factor, farthest sixth", map.name, farthestPerspective);
      lesson.measure("share of pixels wrong by more than 0.05", map.name, "/error/covered/fraction_above_0.05");
    }
    lesson.measure("eye depth z_n of the visible receivers", "lispsm", "/light_view/warp/z_near");
    lesson.measure("eye depth z_f of the visible receivers", "lispsm", "/light_view/warp/z_far");

    const auto spread = [&](const char* run, const std::string& nearPointer, const std::string& farPointer) {
      return lesson.value(run, nearPointer) / lesson.value(run, farPointer);
    };
    lesson.observation(spread("uniform", nearest, farthest) > 10.0
        ? "The uniform map's texel_ratio_t is more than ten times larger on the nearest ground than on the farthest: "
          "the same texel size everywhere, seen from ever closer."
        : "The uniform map's texel_ratio_t does not differ tenfold between the nearest and farthest ground here.");
    lesson.observation(lesson.value("lispsm", nearest) < lesson.value("uniform", nearest) &&
          lesson.value("psm", nearest) < lesson.value("uniform", nearest)
        ? "Both warps make the nearest ground's texels smaller on the screen than the uniform map's: they move texels "
          "from the far ground toward the eye."
        : "The warps do not make the nearest ground's texels smaller than the uniform map's here.");
    lesson.observation(spread("lispsm", nearestPerspective, farthestPerspective) <
          spread("uniform", nearestPerspective, farthestPerspective) / 4.0
        ? "LiSPSM narrows the spread of Eq. 1's perspective factor between the nearest and farthest ground to less "
          "than a quarter of the uniform map's (n_opt equalises it at z_n and z_f, Fig. 12)."
        : "LiSPSM does not narrow the perspective factor's spread to a quarter of the uniform map's here.");
    const double psmSpread = spread("psm", nearest, farthest);
    lesson.observation(psmSpread > 0.9 && psmSpread < 1.1 && spread("lispsm", nearest, farthest) > 2.0
        ? "On the ground PSM's texel_ratio_t is the same at the nearest and farthest depths, LiSPSM's still falls "
          "with the distance: the ground's projection factor falls as the eye height over the depth, which cancels "
          "the growth of PSM's perspective error exactly (PSM is a uniform map in the eye's post-perspective space, "
          "where the screen and the map both see the ground as one plane at one scale). Fig. 12 favours LiSPSM for "
          "surfaces that face the eye; on a ground seen from eye height PSM's stronger warp spreads the texels evenly "
          "over the screen."
        : "On the ground PSM's texel_ratio_t is not the same at the nearest and farthest depths here.");
    const auto wrong = [&](const char* run) { return lesson.value(run, "/error/covered/fraction_above_0.05"); };
    lesson.observation(wrong("lispsm") < wrong("uniform") && wrong("psm") < wrong("uniform")
        ? "Both warps misclassify fewer pixels than the uniform map of the same size: the stair steps of the near "
          "shadows shrink."
        : "The warps do not misclassify fewer pixels than the uniform map at this size.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Write the LiSPSM run with its buffers and read texel_ratio_s beside texel_ratio_t (the axis the "
                   "warp leaves across the view):",
      lesson.renderCommand("lispsm", "out/lispsm"));
    lesson.tryNext("Turn the light behind the viewer (deep-view-behind, 15 degrees off the view): the angle gamma "
                   "between view and light shrinks, n grows as n_opt / sin(gamma), and the warp fades toward the "
                   "uniform map:",
      "shadowlab render datasets/deep-view-behind/scene.json -t hard --set shadow_map_size=512 --set warp=lispsm -r " +
        resolution + " --out out/lispsm-behind");
    lesson.tryNext("The survey's Fig. 12 itself, texel_ratio_t per depth bin beside its closed forms, on tiles that "
                   "face the eye and the light:",
      "shadowlab bench datasets/facing-tiles/scene.json -t hard --set shadow_map_size=512 --sweep "
      "'warp+warp_n=lispsm+1e6,psm+0,lispsm+0' --depth-profile texel_ratio_t --depth-bins 20 --depth-range 1,100 "
      "-r 256x64 --repeat 1 --reference-samples 1 --out out/fig12");
  };
  return lesson;
}

} // namespace sl
