// Lesson: packets, coherence and hierarchy (Yang, Feng, Guennebaud & Liu 2009, §4.1-4.3, Alg. 1-3, Fig. 8): yfgl09
// extracts contours through a dual-grid MSSM instead of visiting every cell of the kernel, and does it once for a
// packet of w x h pixels whose kernels are coherent.
#include "lessons/Lesson.h"
#include "lessons/LessonBuilder.h"

namespace sl
{

Lesson packetsHierarchyLesson()
{
  Lesson lesson{ "packets-coherence-hierarchy", "Packets, coherence and hierarchy: visited nodes",
    "Contour back-projection visits every cell of a kernel that can reach hundreds of texels; how much "
    "of that work do a hierarchy and pixel packets save, without changing the answer?" };
  lesson.build = [](LessonBuilder& lesson) {
    lesson.sceneNote(
      "`stacked-occluders`: two squares under a 1.2-wide light, whose penumbrae need wide kernels. `yfgl09` finds the "
      "contour edges of the occluders in each pixel's kernel. With `hierarchy=off` it visits every dual cell of the "
      "kernel (the brute force); with `hierarchy=on` it walks a min-max hierarchy (the dual-grid MSSM, §4.2, Alg. 3) "
      "and skips the nodes that cannot hold a contour. With 3 x 3 packets (§4.1) a packet whose kernels are "
      "coherent (Eq. 2; predicted by Eq. 5-6, §4.3) is traversed once for its 9 pixels. `visited_nodes` counts, "
      "per pixel, the nodes or cells examined for it (its share of its packet's traversal). Every run uses a "
      "512-texel map; the visibility is the same in all of them.");
    lesson.render({ "brute-force", "stacked-occluders", "yfgl09",
      { "shadow_map_size=512", "hierarchy=off", "packet_width=1", "packet_height=1" }, {}, "" });
    lesson.render({ "hierarchy", "stacked-occluders", "yfgl09",
      { "shadow_map_size=512", "hierarchy=on", "packet_width=1", "packet_height=1" }, {}, "brute-force" });
    lesson.render({ "hierarchy-packets", "stacked-occluders", "yfgl09", { "shadow_map_size=512" }, {}, "brute-force" });

    lesson.montage("visited_nodes", "**Nodes visited per pixel, on one scale.** The brute force, the hierarchy, the "
      "hierarchy with 3 x 3 packets.", { "brute-force", "hierarchy", "hierarchy-packets" }, "visited_nodes");
    lesson.montage("packet_class", "**How each pixel's packet was computed** (§4.3): trivial (lit or umbra), coherent "
      "packet, predicted non-coherent, caught by a null status (Eq. 3), over budget.", { "hierarchy-packets" },
      "packet_class");
    lesson.probe("probe", "**The pixel that visits most nodes, inside:** the hierarchy's nodes it visited, by level "
      "and decision, and the contour edges they gave.", "hierarchy-packets", LessonPixel::largestValue("visited_nodes"));

    for (const char* run : { "brute-force", "hierarchy", "hierarchy-packets" })
    {
      lesson.measure("mean visited nodes per pixel", run, "/buffers/visited_nodes/mean");
      lesson.measure("largest visited nodes", run, "/buffers/visited_nodes/max");
      lesson.measure("GPU time of the frame (ms)", run, "/total_gpu_ms");
    }
    for (const char* run : { "hierarchy", "hierarchy-packets" })
    {
      lesson.measure("largest visibility difference from the brute force", run, "/error/covered/max_abs_error");
    }
    lesson.measure("non-trivial packets", "hierarchy-packets", "/technique_statistics/packets_non_trivial");
    lesson.measure("coherent packets (% of the non-trivial)", "hierarchy-packets",
      "/technique_statistics/coherent_packet_percent");
    lesson.measure("median penumbra kernel (texels)", "hierarchy-packets",
      "/technique_statistics/median_penumbra_kernel_texels");

    const auto visited = [&](const char* run) { return lesson.value(run, "/buffers/visited_nodes/mean"); };
    lesson.observation(visited("hierarchy") < visited("brute-force")
        ? "The hierarchy visits fewer nodes than the brute force visits cells: whole blocks of the kernel with no "
          "contour in them are skipped at a coarse level."
        : "The hierarchy does not visit fewer nodes than the brute force here: the kernels are too small to prune.");
    lesson.observation(visited("hierarchy-packets") < visited("hierarchy")
        ? "Packets lower the count again: a coherent packet's traversal is shared by its pixels."
        : "Packets do not lower the count here: few packets were coherent, and the others went pixel by pixel.");
    lesson.observation(lesson.value("hierarchy-packets", "/error/covered/max_abs_error") < 1e-3
        ? "The visibility is the same with and without hierarchy and packets (to float rounding): they change the "
          "work, not the answer."
        : "The visibility differs from the brute force's by more than float rounding somewhere: see the table.");

    const std::string resolution = lesson.resolutionText();
    lesson.tryNext("Force packets (no coherence prediction) and see how many are coherent after all:",
      "shadowlab render datasets/stacked-occluders/scene.json -t yfgl09 --set shadow_map_size=512 --set "
      "coherence_test=off -r " + resolution + " --out out/forced-packets");
    lesson.tryNext("The near-light occluder, where kernels are widest and the hierarchy pays most:",
      "shadowlab bench datasets/near-light/scene.json -t yfgl09 --set shadow_map_size=256 --sweep hierarchy=off,on -r " +
        resolution + " --repeat 1 --reference-samples 64 --out out/near-light-hierarchy");
    lesson.tryNext("Write two runs and compare visited_nodes yourself:",
      lesson.renderCommand("hierarchy", "out/hierarchy") + " && " +
        lesson.renderCommand("hierarchy-packets", "out/hierarchy-packets") +
        " && shadowlab montage out/hierarchy out/hierarchy-packets --buffer visited_nodes --out visited_nodes.png");
  };
  return lesson;
}

} // namespace sl
