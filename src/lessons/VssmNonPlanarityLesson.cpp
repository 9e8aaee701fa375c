// Lesson: VSSM's non-planarity (Yang et al. 2010, §5, Alg. 1-2, Fig. 3): a kernel whose depths are not one plane is
// split into sub-kernels; where a sub-kernel is still non-planar (E(x) >= t) it is filtered point by point.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson vssmNonPlanarityLesson()
{
  Lesson lesson{ "vssm-non-planarity", "VSSM's non-planarity: sub-kernels where one plane is not enough",
    "VSSM estimates blockers and visibility from the mean and variance of a kernel, which assumes the "
    "blockers form one plane; how does it find the kernels where they do not, and what does splitting "
    "them buy?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "VSSM (Yang et al. 2010) takes the average blocker depth from a summed-area table of moments instead of PCSS's "
      "search (Eq. 4), and the visibility from Chebyshev's bound over the penumbra kernel. Both read only the mean "
      "and variance of the kernel, which describe it fully only when the blockers are planar (Fig. 3 a: VSM's lit "
      "assumption). Where the mean is not below the receiver (E(x) >= t), §5 splits the kernel into sub-kernels, "
      "uniformly or by an adaptive quad-tree (Alg. 2), and filters the non-planar ones by PCF. `stacked-occluders` "
      "has two blockers at different depths over the same receivers. The run `planar-assumption` turns both "
      "subdivisions off; `vssm` is the paper's configuration (uniform 5 x 5 blocker sub-kernels, an adaptive "
      "quad-tree of height 3 for the visibility). Both use a 1024-texel map.");
    lesson.reference("reference", "stacked-occluders");
    lesson.render({ "planar-assumption", "stacked-occluders", "vssm",
      { "shadow_map_size=1024", "blocker_subdivision=none", "shadow_subdivision=none" }, {}, "reference" });
    lesson.render({ "vssm", "stacked-occluders", "vssm", { "shadow_map_size=1024" }, {}, "reference" });

    lesson.montage("classification", "**How each pixel was decided** (Alg. 1: lit or umbra from the hierarchical "
      "shadow map, penumbra, or contact).", { "planar-assumption", "vssm" }, "classification");
    lesson.montage("subkernels_mean_not_in_front", "**Sub-kernels whose mean is not in front of the receiver, per "
      "pixel** (E(x) >= t, §5.1's non-planarity test; both steps, quad-tree nodes included): where the planar "
      "assumption was questioned. Most of these sub-kernels are then found lit by the variance threshold; only the "
      "non-planar leaves are filtered point by point, next figure.", { "planar-assumption", "vssm" },
      "subkernels_mean_not_in_front");
    lesson.montage("pcf_samples", "**Point-sampled comparisons per pixel** (`pcf_samples`: the non-planar leaves' "
      "PCF and the contact PCF): where VSSM fell back to point samples.", { "planar-assumption", "vssm" }, "pcf_samples");
    lesson.errorMontage("error", "**Error against the reference** (blue = too dark, red = too bright).",
      { "planar-assumption", "vssm" });
    lesson.probe("probe", "**The pixel with the most sub-kernels whose mean is not in front of the receiver, "
      "inside:** its kernels, their sub-kernels and which of them were lit, refined or filtered point by point.",
      "vssm", LessonPixel::largestValue("subkernels_mean_not_in_front"));

    for (const char* run : { "planar-assumption", "vssm" })
    {
      lesson.measure("penumbra pixels (classification)", run, "/buffers/classification/category_pixels/penumbra");
      lesson.measure("mean sub-kernels with E(x) >= t", run, "/buffers/subkernels_mean_not_in_front/mean");
      lesson.measure("mean quad-tree nodes visited", run, "/buffers/quadtree_nodes_visited/mean");
      lesson.measure("mean point-sampled comparisons", run, "/buffers/pcf_samples/mean");
      lesson.measure("RMSE over the penumbra", run, "/error/penumbra/rmse");
      lesson.measure("RMSE over every covered pixel", run, "/error/covered/rmse");
      lesson.measure("GPU time of the frame (ms)", run, "/total_gpu_ms");
    }

    lesson.observation(lesson.value("vssm", "/error/penumbra/rmse") < lesson.value("planar-assumption", "/error/penumbra/rmse")
        ? "Splitting the kernels lowers the penumbra error against the ray tracer: the sub-kernels that are planar "
          "get the right blocker depth, and the non-planar leaves are point-sampled instead of assumed lit."
        : "Splitting the kernels does not lower the penumbra error here.");
    lesson.observation(lesson.value("vssm", "/buffers/subkernels_mean_not_in_front/mean") >
          lesson.value("vssm", "/buffers/pcf_samples/mean")
        ? "The subdivided run questions many more sub-kernels (E(x) >= t) than it point-samples: most of them are "
          "then lit by the variance threshold (§6.5), and only a few leaves fall back to PCF."
        : "The subdivided run point-samples more comparisons than it questions sub-kernels here.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Uniform against adaptive subdivision of the visibility kernel (§6.2):",
      "shadowlab bench datasets/stacked-occluders/scene.json -t vssm --set shadow_map_size=1024 --sweep "
      "shadow_subdivision=none,uniform,adaptive -r " + resolution + " --repeat 1 --reference-samples 64 --out out/vssm-subdivision");
    lesson.tryNext("The contact case of §6.4, where the blocker touches the receiver:",
      "shadowlab render datasets/contact/scene.json -t vssm --set shadow_map_size=1024 -r " + resolution +
        " --out out/vssm-contact");
    lesson.tryNext("Write the subdivided run with its buffers (classification, subkernels_mean_not_in_front, "
                   "quadtree_nodes_visited, pcf_samples):",
      lesson.renderCommand("vssm", "out/vssm"));
  };
  return lesson;
}

} // namespace sl
