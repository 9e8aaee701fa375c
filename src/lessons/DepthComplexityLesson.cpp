// Lesson: depth complexity sampling (Forest, Barthe & Paulin 2008, as used by Forest et al. 2009 §3.2): every light
// sample gets the number of occluders between the point and it, from the centre's shadow-volume count and the
// silhouette wedges; visibility is the share of samples at count 0. Exact per sample, so what is left is sampling
// noise, which the pattern and N decide (Forest et al. 2009 Fig. 5).
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson depthComplexityLesson()
{
  Lesson lesson{ "depth-complexity", "Depth complexity sampling: counting occluders per light sample",
    "How does `dcs` count the occluders between a point and each light sample, and how much of its "
    "error is left to the sampling pattern?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`stacked-occluders` puts two squares at different heights between a square light and the ground, so a point "
      "can see 0, 1 or 2 occluders (4 triangles) toward different parts of the light. `dcs` counts, for every "
      "sample, the caster triangles on the segment: the light centre's count comes from its shadow volumes "
      "(`depth_complexity_center`); every potential silhouette edge then draws a wedge, and a fragment inside it "
      "adds the edge's multiplicity to the samples whose path from the centre crosses the edge's shadow "
      "(`DcsGeometry.h`). `dc_max` is the largest count over the samples, `wedges_covering` the wedges that "
      "reached the point. Visibility is the share of samples with count 0, so the counts are exact and only the "
      "choice of samples (pattern, N) separates `dcs` from the ray-traced truth.");
    lesson.reference("reference", "stacked-occluders");
    lesson.render({ "grid-16", "stacked-occluders", "dcs", { "light_samples=grid", "samples=16" }, {}, "reference" });
    lesson.render({ "poisson-16", "stacked-occluders", "dcs", { "light_samples=poisson", "samples=16" }, {}, "reference" });
    lesson.render({ "poisson-64", "stacked-occluders", "dcs", { "light_samples=poisson", "samples=64" }, {}, "reference" });

    lesson.montage("counts", "**dc_max**: the most occluder triangles toward any one light sample (the centre's own "
      "count is `depth_complexity_center`); the shadow volume from the centre alone misses what only some samples "
      "see.", { "poisson-16" }, "dc_max");
    lesson.montage("wedges", "**wedges_covering**: how many silhouette wedges contain each point, the per-pixel "
      "cost of the wedge pass.", { "poisson-16" }, "wedges_covering");
    lesson.errorMontage("error", "**Visibility against the ray-traced reference** for a 4x4 grid, 16 Poisson samples "
      "and 64 Poisson samples (red = too bright, blue = too dark): the counts are exact, the noise is the pattern's.",
      { "grid-16", "poisson-16", "poisson-64" });
    lesson.probe("probe", "**The pixel with the most occluders toward one sample, inside:** the centre's crossings, "
      "each wedge containing the point with its multiplicity, and every sample's count on the light.",
      "poisson-16", LessonPixel::largestValue("dc_max"));

    lesson.measure("largest count toward the centre", "poisson-16", "/buffers/depth_complexity_center/max");
    lesson.measure("largest count toward a sample", "poisson-16", "/buffers/dc_max/max");
    lesson.measure("mean count toward the centre", "poisson-16", "/buffers/depth_complexity_center/mean");
    lesson.measure("mean count toward the most occluded sample", "poisson-16", "/buffers/dc_max/mean");
    lesson.measure("smallest count (negative: topology error)", "poisson-16", "/buffers/dc_min/min");
    lesson.measure("potential silhouette edges", "poisson-16", "/technique_statistics/potential_silhouette_edges");
    lesson.measure("silhouette edges from the centre", "poisson-16", "/technique_statistics/silhouette_edges_centre");
    lesson.measure("mean wedges per point", "poisson-16", "/buffers/wedges_covering/mean");
    for (const char* run : { "grid-16", "poisson-16", "poisson-64" })
    {
      lesson.measure("RMSE against the reference", run, "/error/covered/rmse");
      lesson.measure("penumbra RMSE", run, "/error/penumbra/rmse");
    }

    lesson.observation(lesson.value("poisson-16", "/buffers/dc_max/mean") >
          lesson.value("poisson-16", "/buffers/depth_complexity_center/mean")
        ? "On average a point's most-occluded sample sees more occluders than its centre does: a single shadow "
          "volume from the centre cannot tell those points apart, the wedges can."
        : "On average no sample sees more occluders than the centre here.");
    lesson.observation(lesson.value("poisson-16", "/buffers/dc_min/min") >= 0.0
        ? "No count went negative: the casters' edges were all accounted for."
        : "A count went negative: some caster edge was missed (a topology error).");
    lesson.observation(lesson.value("poisson-64", "/error/covered/rmse") < lesson.value("poisson-16", "/error/covered/rmse")
        ? "Four times the samples lower the error, as sampling noise should; the count itself was already exact."
        : "64 samples did not lower the error below 16 here.");
    lesson.observation(lesson.value("poisson-16", "/error/penumbra/rmse") < lesson.value("grid-16", "/error/penumbra/rmse")
        ? "At 16 samples the shifted Poisson pattern has a lower penumbra error than the shifted grid here."
        : "At 16 samples the shifted grid is as good as the Poisson pattern in this penumbra.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Compare every pattern at N = 16 and 64 against the ray tracer (Forest et al. 2009, Fig. 5):",
      "shadowlab bench datasets/stacked-occluders/scene.json -t dcs --sweep light_samples=grid,stratified,poisson,zero_two,poisson_4x4 "
      "--sweep samples=16,64 -r " + resolution + " --repeat 1 --reference-samples 256 --out out/dcs-patterns");
    lesson.tryNext("Trace the same samples and get every sample's crossing count from Embree:",
      "shadowlab reference datasets/stacked-occluders/scene.json --light-samples poisson --reference-samples 16 -r " + resolution +
        " --out out/dcs-reference");
    lesson.tryNext("Write the run with every sample's count and open `sample_depth_complexity` in ParaView:",
      "shadowlab render datasets/stacked-occluders/scene.json -t dcs --set export_sample_counts=1 -r " + resolution +
        " --out out/dcs-counts");
  };
  return lesson;
}

} // namespace sl
