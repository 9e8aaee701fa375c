// Lesson: back-projection overlap and multi-view (Guennebaud et al. 2006 and 2007; Yang et al. 2009 §5): back-projecting
// the shadow map onto the light counts what ONE view from the light's centre saw. GBP06 sums the areas of its
// micropatches, so patches whose projections overlap on the light are counted twice; GBP07 integrates the contour
// of the occluded region, which counts each point of the light once; neither sees what the centre's view hides, and
// S x S sub-lights, each with its own map, see more of it.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson backProjectionLesson()
{
  Lesson lesson{ "backprojection-multiview", "Back-projection: overlap and multi-view",
    "Back-projection measures how much of the light the shadow map's occluders cover; where does it "
    "count an occluder twice, where does it miss one, and what do sub-lights fix?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`bunny`: the Stanford bunny under a 0.6-wide square light. Its ears and body shadow each other: seen from the "
      "light's centre, one surface hides another, and the shadow map keeps only the nearest. `gbp06` back-projects "
      "every occluding texel of the kernel as a micropatch and sums the covered areas of the light, with gap "
      "filling (Guennebaud et al. 2006): where two micropatches' projections overlap, the overlap is counted twice "
      "and the pixel is too dark. `gbp07` extracts the contour of the occluded texels and integrates it radially "
      "(Guennebaud et al. 2007), covering each point of the light once. Both see only the centre's view; "
      "`sublights=2` splits the light into 2 x 2 sub-lights, each with its own focused map, and averages them "
      "(Yang et al. 2009 §5). Every run uses 512-texel maps.");
    lesson.reference("reference", "bunny");
    lesson.render({ "gbp06", "bunny", "gbp06", { "shadow_map_size=512" }, {}, "reference" });
    lesson.render({ "gbp07", "bunny", "gbp07", { "shadow_map_size=512" }, {}, "reference" });
    lesson.render({ "gbp07-sublights-2", "bunny", "gbp07", { "shadow_map_size=512", "sublights=2" }, {}, "reference" });

    lesson.montage("visibility", "**Visibility** (1 = lit).", { "reference", "gbp06", "gbp07", "gbp07-sublights-2" },
      "visibility");
    lesson.errorMontage("error", "**Error against the reference** (blue = too dark: occluders counted twice; red = "
      "too bright: occluders the view from the centre did not see).", { "gbp06", "gbp07", "gbp07-sublights-2" });
    lesson.probe("probe", "**The contour run's worst pixel, inside:** the contour edges back-projected onto the "
      "light plane and the part of the light they cover.", "gbp07", LessonPixel::largestError());

    lesson.measure("mean visibility", "reference", "/buffers/visibility/mean");
    for (const char* run : { "gbp06", "gbp07", "gbp07-sublights-2" })
    {
      lesson.measure("mean visibility", run, "/buffers/visibility/mean");
      lesson.measure("RMSE over the penumbra", run, "/error/penumbra/rmse");
      lesson.measure("RMSE over every covered pixel", run, "/error/covered/rmse");
      lesson.measure("GPU time of the frame (ms)", run, "/total_gpu_ms");
    }
    lesson.measure("mean occluding micropatches", "gbp06", "/buffers/occluding_texels/mean");
    lesson.measure("mean contour edges", "gbp07", "/buffers/contour_edges/mean");
    lesson.measure("mean contour edges (summed over sub-lights)", "gbp07-sublights-2", "/buffers/contour_edges/mean");

    const auto penumbra = [&](const char* run) { return lesson.value(run, "/error/penumbra/rmse"); };
    lesson.observation(penumbra("gbp07") < penumbra("gbp06")
        ? "Contours err less than micropatches over the penumbra: integrating the outline of the occluded region "
          "covers each point of the light once, where summing micropatches counts overlaps twice."
        : "Micropatches do not err more than contours over the penumbra here.");
    lesson.observation(lesson.value("gbp06", "/buffers/visibility/mean") < lesson.value("gbp07", "/buffers/visibility/mean")
        ? "The micropatch run is darker on average than the contour run: the overlaps it counts twice (blue in its "
          "error panel where the contour run's is white)."
        : "The micropatch run is not darker on average than the contour run here.");
    const double truth = lesson.value("reference", "/buffers/visibility/mean");
    lesson.observation(lesson.value("gbp06", "/buffers/visibility/mean") > truth &&
          lesson.value("gbp07", "/buffers/visibility/mean") > truth
        ? "Both single-view runs are brighter on average than the reference: what the shadow map's one view from the "
          "light's centre hides (the surfaces behind the nearest one) casts no shadow in them."
        : "The single-view runs are not both brighter on average than the reference here.");
    lesson.observation(penumbra("gbp07-sublights-2") < penumbra("gbp07")
        ? "Four sub-lights lower the penumbra error further: each sees parts of the bunny the centre's view hid, at the "
          "price of four maps and four passes (compare the GPU times)."
        : "Four sub-lights do not lower the penumbra error here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Sub-lights 1, 2 and 4 with the packet-based traversal (same visibility as gbp07, faster):",
      "shadowlab bench datasets/bunny/scene.json -t yfgl09 --set shadow_map_size=512 --sweep sublights=1,2,4 -r " +
        resolution + " --repeat 1 --reference-samples 64 --out out/sublights");
    lesson.tryNext("Grow the light: the hidden surfaces matter more as the light widens:",
      "shadowlab render datasets/bunny/scene.json -t gbp07 --set shadow_map_size=512 --scene-set /lights/0/size=1.5 -r " +
        resolution + " --out out/bunny-wide-light");
    lesson.tryNext("Gap filling off: the cracks between micropatches of different depths let light through:",
      "shadowlab render datasets/bunny/scene.json -t gbp06 --set shadow_map_size=512 --set gap_filling=off -r " +
        resolution + " --out out/gbp06-no-gap-filling");
  };
  return lesson;
}

} // namespace sl
