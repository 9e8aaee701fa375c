// Technique `vssm`: variance soft shadow mapping (Yang et al. 2010): Alg. 1 with the HSM early-out, the
// average blocker depth of Eq. 4 (z_unocc = t), kernel subdivision (§5: uniform m x m, adaptive Alg. 2 by
// stackless linear quad-tree traversal, or none = VSM's lit assumption, Fig. 3a), the §6.4 contact-shadow
// fallback (per pixel on Eq. 4's blocker depth, or per sub-kernel of w_p on its own mean: contact_test) and the
// §6.5 lit threshold. Math: vssm/shaders/VssmVisibility.glsl.
// Parameters: the shadow-map ones, receiver_plane_bias, sat_precision, hsm (mipmap | nbuffers, §6.1; ysm, SS08 §6),
// hsm_early_out, blocker_subdivision + blocker_uniform_m + blocker_tree_height, shadow_subdivision +
// shadow_uniform_n + shadow_tree_height (default: the paper's mixed scheme m = 5, H = 3, §6.3),
// nonplanar_pcf_taps (2: 2 x 2), lit_variance_threshold (x r), contact_threshold (x r), contact_test
// (blocker_average | subkernel_mean), min_variance.
// Buffers: blocker_kernel_texels, penumbra_kernel_texels, avg_blocker_depth, classification
// (not tested / lit / umbra / penumbra / contact: the §6.4 PCF decided the pixel, or with subkernel_mean at
// least one of its sub-kernels), subkernels_mean_not_in_front, quadtree_nodes_visited,
// pcf_samples (eight outputs in all, GL's guaranteed draw-buffer count).
#pragma once

#include "frame/ProbeRecord.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "structures/sat/SatStructure.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/SummedAreaTable.h"

#include <cstdint>
#include <optional>

namespace sl
{

struct FrameResult; // frame/FrameResult.h

TechniqueDescriptor vssmTechnique();

// How a pixel was decided: the `classification` buffer's categories (code = the enumerator's value, shader
// identifier = its name in upper case: CLASSIFICATION_CONTACT, ...), generated into the shader from here.
enum class VssmClass
{
  NotTested = 0,
  Lit = 1,
  Umbra = 2,
  Penumbra = 3,
  Contact = 4
};

// The linear quad-tree of Alg. 2 (Bunnell 2005): nodes (x, y, level) of a full quad-tree of height H in
// depth-first order, each with the index of its first child (Child; -1 for leaves) and of the node that
// follows its subtree (Next; -1 = Null). The GLSL computes both from (x, y, level); this table is what
// they must equal.
struct QuadTreeNode
{
  glm::ivec3 cell{ 0 }; // x, y, level
  int child = -1;
  int next = -1;
};
std::vector<QuadTreeNode> linearQuadTree(int height);
// The arithmetic pointers of VssmVisibility.glsl (nullopt = Null).
glm::ivec3 quadTreeChild(glm::ivec3 node);
std::optional<glm::ivec3> quadTreeNext(glm::ivec3 node);

// What the CPU reference reads: the G-buffer and shadow map, the HSM (rebuilt from the shadow map) and the
// summed-area table the GPU built (read back: its precision is an input, like the shadow map).
// The sub-kernel schemes of blocker_subdivision and shadow_subdivision (§5; the shaders' SCHEME_* codes).
enum class VssmSubdivision
{
  None,    // VSM's lit assumption
  Uniform, // n x n sub-kernels
  Adaptive // Alg. 2's quad-tree
};

// The `contact_test` choices (§6.4).
enum class VssmContactTest
{
  BlockerAverage, // d - z_occ of Eq. 4 < eps, once per pixel
  SubkernelMean   // t_c - E(x) < eps for each normal sub-kernel of w_p
};

// One step's subdivision: its scheme, the uniform scheme's cells per axis, the adaptive scheme's tree height.
struct VssmSubdivisionSettings
{
  VssmSubdivision scheme{};
  int uniformCells{};
  int treeHeight{};
};

// vssm's parameters, typed (parsed once, by from()); the HSM's own are HierarchicalShadowMapSettings.
struct VssmSettings
{
  BiasSettings bias;
  bool receiverPlaneBias{};
  SummedAreaTableSettings sat;
  bool hsmEarlyOut{};
  VssmSubdivisionSettings blockerSubdivision;
  VssmSubdivisionSettings shadowSubdivision;
  int nonplanarPcfTaps{};        // per axis
  double litVarianceThreshold{}; // times r, the scene's bounding radius
  double contactThreshold{};     // times r
  VssmContactTest contactTest{};
  double minVariance{};          // relative to d^2

  static VssmSettings from(const ParameterValues& values);
};

struct VssmReferenceInputs
{
  const ShadowMapInputs* shadowMap = nullptr;
  HierarchicalShadowMap hsm;
  std::optional<Image<std::uint32_t>> integerTable; // sat_precision = int32
  ImageF floatTable;                                // float_centred: 2 components
  double sceneRadius = 0.0;
  double satHalfStep = 0.0;

  BoxMoments boxMoments(glm::ivec2 lo, glm::ivec2 hi) const;
};
VssmReferenceInputs vssmReferenceInputs(const ShadowMapInputs& shadowMap, const ParameterValues& values,
  const std::optional<Image<std::uint32_t>>& integerTable, const ImageF& floatTable, double sceneRadius);
// The float SAT the GPU built, read back from the frame's light-space arrays sat_z and sat_z2 (2 components).
ImageF floatSummedAreaTableOf(const FrameResult& frame);
// vssmReferenceInputs of a rendered frame: the SAT the GPU built as read back (the exact int32 table, else the
// float arrays), the frame's parameters and the scene's bounding-sphere radius r. The tests and the probe read
// the frame through this.
VssmReferenceInputs vssmReferenceInputsOf(const FrameResult& frame, const Scene& scene, const ShadowMapInputs& shadowMap);
// The int32 SAT's half fixed-point step of the depth range (0 for float), as the pass sets it.
double vssmSatHalfStep(bool integer, int mapSize, double nearDepth, double farDepth);

struct VssmSample
{
  ReferenceSample sample;
  VssmClass classification = VssmClass::NotTested;
  double blockerKernelTexels = 0.0;
  double penumbraKernelTexels = 0.0;
  double averageBlockerDepth = 0.0;
  int subkernelsMeanNotInFront = 0;
  int quadtreeNodesVisited = 0;
  int pcfSamples = 0;
  double kernelEdgeMargin = 1e300;
  // Smallest relative distance of a continuous decision (E(x) >= t, the variance threshold, the blocked-
  // area threshold, the contact test, the HSM tests) to its boundary; float may decide otherwise below ~1e-4.
  double decisionMargin = 1e300;
};

// CPU reference (double precision) of VssmVisibility.glsl at pixel (x, y). `recorder` (optional, `shadowlab
// probe`): every step in the order Alg. 1 takes them: the receiver, the blocker search kernel w_i (L7), the HSM
// test (L8-10), w_i's sub-kernels with their class and moments (L11-15, §5, Alg. 2; adaptive: the quad-tree
// nodes visited), the average blocker depth (Eq. 4-5), the penumbra kernel w_p (L16), the §6.4 contact test,
// w_p's sub-kernels (L17-20), the PCF taps, the visibility (Alg. 2 L29-32), and the buffers' values under their
// names (group "result").
VssmSample vssmReference(const VssmReferenceInputs& inputs, const VssmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
