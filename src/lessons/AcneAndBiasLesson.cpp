// Lesson: shadow acne and depth bias, measured by hard's depth_margin (receiver depth - bias - stored caster depth;
// survey Scherzer et al. 2011 §5) and by the error against exact hard shadows (stencil shadow volumes, z-fail); beside
// the bias, the survey's alternatives that change the depth compared (depth_layer = midpoint, dual).
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson acneAndBiasLesson()
{
  Lesson lesson{ "acne-and-bias", "Acne and bias: depth_margin with the bias off, on, too large, and midpoint and dual maps",
    "Why does a lit surface shadow itself in speckles (acne) when a shadow map is compared without a "
    "bias, and what does too much bias do instead?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`grazing`: a small box on the ground under a light about 80 degrees from the ground's normal, the case where "
      "the ground's depth changes fastest from one shadow-map texel to the next. A texel stores one depth for its "
      "whole footprint, and a receiver point inside the footprint compares its own depth against it: on a sloped "
      "footprint half of the points lie behind the stored depth and shadow themselves. `depth_margin` is the "
      "comparison itself (receiver depth - bias - stored depth: > 0 shadowed), so acne is where it is positive on "
      "a lit surface. The bias (`bias_constant_texels` plus `bias_slope_texels` times the slope, in texel "
      "footprints) moves the comparison back; too much of it lets light under the caster's foot (*peter panning*). "
      "The truth is the exact hard shadow of the light's centre, from stencil shadow volumes (`shadow-volume`), "
      "which have no depth map and so no acne.");
    lesson.render({ "exact", "grazing", "shadow-volume", {}, {}, "" });
    lesson.render({ "bias-off", "grazing", "hard",
      { "shadow_map_size=1024", "bias_constant_texels=0", "bias_slope_texels=0" }, {}, "exact" });
    lesson.render({ "bias-default", "grazing", "hard", { "shadow_map_size=1024" }, {}, "exact" });
    lesson.render({ "bias-large", "grazing", "hard",
      { "shadow_map_size=1024", "bias_constant_texels=16", "bias_slope_texels=16" }, {}, "exact" });
    // Survey §5's alternatives to a bias: the depth compared is not the nearest caster's.
    lesson.render({ "midpoint", "grazing", "hard",
      { "shadow_map_size=1024", "bias_constant_texels=0", "bias_slope_texels=0", "depth_layer=midpoint" }, {}, "exact" });
    lesson.render({ "dual", "grazing", "hard",
      { "shadow_map_size=1024", "bias_constant_texels=0", "bias_slope_texels=0", "depth_layer=dual" }, {}, "exact" });
    lesson.render({ "polygon-id", "grazing", "hard", { "shadow_map_size=1024", "depth_layer=polygon_id" }, {}, "exact" });
    lesson.sceneNote(
      "Without any bias, the map can store another depth (survey §5, \"depth biasing\"). `midpoint` (Woo 1992) "
      "stores (z1 + z2) / 2, halfway between the nearest surface and the next one behind it (found by depth peeling): "
      "a lit surface is the nearest one at its texel, so its own depth lies half a layer gap in front of the stored "
      "one, and no acne. `dual` (Weiskopf & Ertl 2003, as the survey summarises them) caps that gap at "
      "`dual_max_offset_texels` texel footprints behind the nearest surface, so a thick gap cannot hide a receiver "
      "lying in it. Both runs have the bias off; `depth_margin` is the receiver's depth minus the depth compared. "
      "`polygon-id` (Hourcade & Nicolas 1985) compares no depth at all: the map stores the id of the nearest triangle, "
      "and a receiver is lit iff that is its own triangle; where a texel holds several triangles (here the ground "
      "quad's two, along its diagonal) it breaks down, and those pixels are flagged (`approximation` code 2).");

    lesson.montage("depth_margin", "**depth_margin on one diverging scale** (white = 0, red = shadowed by the "
      "comparison, blue = lit with room to spare; light grey = no shadow test, faces turned from the light). The "
      "scale is logarithmic in the magnitude beyond its 10th percentile (linear within it), so that the values "
      "around 0, where acne starts, show beside the far-off ones; it ends at the 99.5th percentile of the "
      "magnitudes, and the title gives the share of pixels beyond.",
      { "bias-off", "bias-default", "bias-large", "midpoint", "dual" }, "depth_margin", std::nullopt, 0.1);
    lesson.errorMontage("error", "**Against the exact hard shadow** (blue = too dark: acne or aliasing; red = too "
      "bright: light leaking under the caster).",
      { "bias-off", "bias-default", "bias-large", "midpoint", "dual", "polygon-id" });
    lesson.probe("probe", "**A wrong pixel of the unbiased run, inside:** its receiver depth against the depth the "
      "texel stores (the section shows the texel columns), and the margin between them.", "bias-off",
      LessonPixel::largestError());

    for (const char* run : { "bias-off", "bias-default", "bias-large", "midpoint", "dual" })
    {
      lesson.measure("mean depth bias applied (world units)", run, "/buffers/depth_bias/mean");
      lesson.measure("share of pixels wrong by more than 0.05", run, "/error/covered/fraction_above_0.05");
      lesson.measure("RMSE against the exact hard shadow", run, "/error/covered/rmse");
      lesson.measure("mean visibility", run, "/buffers/visibility/mean");
    }
    lesson.measure("share of pixels wrong by more than 0.05", "polygon-id", "/error/covered/fraction_above_0.05");
    lesson.measure("pixels flagged: several triangles per texel", "polygon-id",
      "/buffers/approximation/category_pixels/polygon id: several triangles per texel");
    lesson.measure("mean visibility", "exact", "/buffers/visibility/mean");

    const auto wrong = [&](const char* run) { return lesson.value(run, "/error/covered/fraction_above_0.05"); };
    lesson.observation(wrong("bias-off") > wrong("bias-default")
        ? "Without a bias, more pixels differ from the exact shadow than with the default bias: the difference is "
          "acne, lit ground that shadows itself."
        : "Without a bias, no more pixels differ from the exact shadow than with the default bias at this map size.");
    lesson.observation(lesson.value("bias-off", "/buffers/visibility/mean") < lesson.value("exact", "/buffers/visibility/mean")
        ? "Acne only darkens: the unbiased run's mean visibility is below the exact one's."
        : "The unbiased run's mean visibility is not below the exact one's here.");
    const bool largeLosesShadow = wrong("bias-large") > wrong("bias-default") &&
      lesson.value("bias-large", "/buffers/visibility/mean") > lesson.value("exact", "/buffers/visibility/mean");
    lesson.observation(largeLosesShadow
        ? "The large bias is wrong on more pixels than the default and brighter on average than the exact shadow: it "
          "pushes the comparison so far back that shadow is lost next to the casters (peter panning; see where in the "
          "error figure). The bias is a trade, not a fix."
        : "The large bias does not lose more shadow than the default here.");

    lesson.observation(wrong("midpoint") < wrong("bias-off") / 10.0 && wrong("dual") < wrong("bias-off") / 10.0
        ? "The midpoint and dual maps, with no bias at all, are wrong on a small fraction of the pixels the unbiased "
          "nearest-depth map gets wrong: the depth they compare with lies behind every lit surface."
        : "The midpoint and dual maps without a bias do not remove most of the unbiased map's errors here.");

    lesson.observation(wrong("polygon-id") < wrong("bias-off") / 10.0
        ? "The polygon-id map, with no depth comparison, is wrong on a small fraction of the pixels the unbiased "
          "depth map gets wrong; what is left lies along triangle edges inside a texel, where it flags the pixels."
        : "The polygon-id map does not remove most of the unbiased map's errors here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sweep the constant bias and watch acne give way to peter panning (the bench's error is against "
                   "a ray-traced reference of the area light, so hard shadows keep a penumbra error):",
      "shadowlab bench datasets/grazing/scene.json -t hard --set bias_slope_texels=0 --sweep "
      "bias_constant_texels=0,0.5,2,8,32 -r " + resolution + " --repeat 1 --reference-samples 64 --out out/bias-sweep");
    lesson.tryNext("A second-depth map (back faces) needs no bias for closed casters (Wang & Molnar 1994):",
      "shadowlab render datasets/grazing/scene.json -t hard --set caster_faces=back --set bias_constant_texels=0 --set "
      "bias_slope_texels=0 -r " + resolution + " --out out/second-depth");
    lesson.tryNext("The layers a midpoint map combines, exported beside it (shadow_map_first_depth, "
                   "shadow_map_second_depth in lightspace.vti):",
      "shadowlab render datasets/grazing/scene.json -t hard --set depth_layer=midpoint --set bias_constant_texels=0 "
      "--set bias_slope_texels=0 -r " + resolution + " --out out/midpoint");
    lesson.tryNext("Write the unbiased run with its buffers and open depth_margin in ParaView (buffers.vti):",
      lesson.renderCommand("bias-off", "out/bias-off"));
  };
  return lesson;
}

} // namespace sl
