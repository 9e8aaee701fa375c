#include "techniques/yfgl09/Yfgl09Technique.h"

#include "techniques/ApproximationRules.h"

#include "structures/hsm/HsmStructure.h"
#include "structures/mssm/DualMssmStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "core/Error.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ContourReceiver.h"
#include "techniques/yfgl09/vtkSLYfgl09Pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <utility>

namespace sl
{

namespace
{

// In code order (checked below).
const Category<PacketClass> packetCategories[] = {
  { PacketClass::NotTested, "NOT_TESTED", "not tested" },
  { PacketClass::Trivial, "TRIVIAL", "trivial (lit or umbra)" },
  { PacketClass::Coherent, "COHERENT", "coherent packet" },
  { PacketClass::NonCoherent, "NON_COHERENT", "non-coherent (predicted)" },
  { PacketClass::CaughtNull, "CAUGHT_NULL", "caught null (Eq. 3)" },
  { PacketClass::OverBudget, "OVER_BUDGET", "packet over the loop budget" },
  { PacketClass::CutShort, "CUT_SHORT", "cut short by the loop cap", true },
};

BufferSpec packetClassBuffer()
{
  return categoricalBuffer("packet_class", "how the pixel was computed (first sub-light)", packetCategories,
    SubLightCombine::First);
}

} // namespace

namespace
{

// The tests' ambiguity rule (Yfgl09Test.cpp): the pixel's own margins (sample, kernel edge, lit / umbra test); the
// packet's other pixels' margins, which can flip the packet's decisions (its class, visited nodes and edges;
// the test compares those allowing 2 % of pixels to differ); and the GPU's marks: a pixel cut short by the loop
// cap is not exact, and a packet pass the cap cut is finished pixel-wise and marked over budget.
std::string yfgl09Ambiguity(const Yfgl09Pixel& result, const std::vector<Yfgl09Pixel>& packet, const FrameResult& frame,
  glm::ivec2 pixel)
{
  if (!result.sample.evaluated)
  {
    return {};
  }
  const auto own = [](const Yfgl09Pixel& r) {
    std::string ambiguity = ambiguityOf(r.sample);
    noteAmbiguity(ambiguity, "kernel edge from a texel centre (texels)", r.kernelEdgeMargin, 1e-4);
    noteAmbiguity(ambiguity, "lit / umbra test from its boundary (relative)", r.decisionMargin, 1e-5);
    return ambiguity;
  };
  std::string ambiguity = own(result);
  for (const Yfgl09Pixel& other : packet)
  {
    const std::string theirs = other.pixel != pixel && other.sample.evaluated ? own(other) : std::string();
    if (!theirs.empty())
    {
      ambiguity += std::string(ambiguity.empty() ? "" : ", ") + "packet pixel " + std::to_string(other.pixel.x) + "," +
        std::to_string(other.pixel.y) + " (" + theirs + "; the packet's decisions may differ)";
    }
  }
  const int gpuClass = static_cast<int>(std::lround(bufferValue(frame, "packet_class", pixel)));
  if (gpuClass == static_cast<int>(PacketClass::CutShort))
  {
    ambiguity += std::string(ambiguity.empty() ? "" : ", ") + "the GPU's loop cap cut this pixel short (packet_class " +
      packetClassLabel(PacketClass::CutShort) + "): its visibility is not exact";
  }
  else if ((gpuClass == static_cast<int>(PacketClass::OverBudget)) != (result.packetClass == PacketClass::OverBudget))
  {
    ambiguity += std::string(ambiguity.empty() ? "" : ", ") +
      "the GPU's packet pass was cut by the loop cap and finished pixel-wise (packet_class " +
      packetClassLabel(PacketClass::OverBudget) + "), or only the twin's packet outgrew the budget: the class and "
      "visited nodes differ, the visibility is exact";
  }
  return ambiguity;
}

} // namespace

Yfgl09Settings Yfgl09Settings::from(const ParameterValues& values)
{
  Yfgl09Settings settings;
  settings.receiver = ContourReceiverSettings::from(values);
  settings.packetWidth = values.getInt("packet_width");
  settings.packetHeight = values.getInt("packet_height");
  settings.hierarchy = values.choice("hierarchy") == "on";
  const std::string& test = values.choice("coherence_test");
  settings.divergenceTest = test == "both" || test == "divergence";
  settings.costTest = test == "both" || test == "cost";
  settings.divergenceThreshold = values.get("divergence_threshold");
  settings.edgeCost = values.get("edge_cost");
  settings.visibilityCost = values.get("visibility_cost");
  settings.paperPacketCost = values.choice("packet_cost") == "paper";
  settings.coherenceDepth = choiceOf<CoherenceDepth>(values, "coherence_depth",
    { { "linear", CoherenceDepth::Linear }, { "comparison", CoherenceDepth::Comparison }, { "window", CoherenceDepth::Window } });
  return settings;
}

TechniqueDescriptor yfgl09Technique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("yfgl09",
    "Packet-based hierarchical soft shadow mapping (contours, packets, dual-grid MSSM traversal)",
    "Yang, Feng, Guennebaud and Liu 2009, §4, Eq. 1-6, Alg. 1-3", 1024);
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.addParameters({
    { "kernel_refinements", 2, 0, 4, "iterations", "times the kernel is shrunk to the minimum occluder depth inside it (Eq. 1 with z_occ_min from the MSSM)", {}, true },
    { "packet_width", 3, 1, 4, "pixels", "packet width w (§4.1; 1 x 1 = pixel-wise, the packet optimisation off)", {}, true },
    { "packet_height", 3, 1, 4, "pixels", "packet height h (§4.1)", {}, true },
    { "hierarchy", 1, 0, 1, "", "contour extraction through the dual-grid MSSM (§4.2, Alg. 3) or every dual cell of the kernel (off: the MSSM-only brute force)", { "off", "on" }, true },
    { "coherence_test", 0, 0, 3, "", "which predictions send a packet pixel-wise before its traversal (§4.3): the divergence probability (Eq. 5 > T_d), the cost model (Eq. 6 > 1), both, or none (null statuses still do)", { "both", "divergence", "cost", "off" }, true },
    { "divergence_threshold", 0.8, 0.0, 1.0, "", "T_d of §4.3 (the paper: 0.8)", {}, false },
    { "edge_cost", 4.0, 0.0, 100.0, "", "Q_e of Eq. 6, cost of extracting an edge relative to visiting a node (Q_n = 1)", {}, false },
    { "visibility_cost", 8.0, 0.0, 100.0, "", "Q_v of Eq. 6, cost of back-projecting and integrating an edge for one pixel (Q_n = 1)", {}, false },
    { "packet_cost", 0, 0, 1, "", "Eq. 6's visibility term for the packet: paper = Q_v w h, every pixel of the packet (Yang et al. 2009 §4.3); penumbra_pixels = Q_v times the packet's penumbra pixels only (trivial pixels integrate nothing)", { "paper", "penumbra_pixels" }, true },
    { "coherence_depth", 0, 0, 2, "", "the depths Eq. 4's P_null compares (§4.3): linear = the packet's pixel depths minus bias against the kernel samples' linear light depths (the text's reading); comparison = the receiver-plane comparison depths over the packet kernel, the range Eq. 3's statuses use; window = the linear reading in the map's window (post-projective, hyperbolic) depth, as a depth buffer stores it", { "linear", "comparison", "window" }, true },
    subLightsParameter(),
    hsmLevelsParameter("mssm_levels", "dual-grid MSSM"),
  });
  descriptor.lightStructures = { &shadowMapStructure(), &dualMssmStructure() };
  // Its ranges (Eq. 1's kernels) and traversals (the packets' kernels, Alg. 3) stay within the farthest receiver's
  // initial kernel but for packets across a depth edge, whose wider regions start from several roots.
  descriptor.lightSpaceRequest = [](const ParameterValues&) {
    LightSpaceRequest request;
    request.minMaxQueriesWithinNearPlaneKernel = true;
    return request;
  };
  descriptor.buffers = {
    { "kernel_texels", "texels", "width of the pixel's kernel (Eq. 1, Fig. 5 left)" },
    { "coherence", "", "Eq. 2 over the pixel's packet: max_i |k_i \\ k_0| / |k_i| (Fig. 5 right)" },
    packetClassBuffer(),
    { "divergence_probability", "", "P_d of the pixel's packet (Eq. 5)" },
    { "visited_nodes", "nodes", "MSSM nodes (or dual cells, hierarchy off) examined for the pixel: its share of its packet's traversal plus its own (Fig. 8; summed over sub-lights)", BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "contour_edges", "edges", "contour edges extracted by the traversal that computed the pixel (summed over sub-lights)", BufferKind::Continuous, {}, SubLightCombine::Sum },
  };
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.coversLightArea = true;
  const int maxPacketPixels = static_cast<int>(descriptor.findParameter("packet_width")->maxValue) *
    static_cast<int>(descriptor.findParameter("packet_height")->maxValue);
  descriptor.shaderConstants = contourKernelShaderConstants();
  descriptor.shaderConstants.insert(descriptor.shaderConstants.end(), {
    { "PACKET_BUDGET", yfgl09PacketBudget, "packet work past which a packet is finished pixel-wise" },
    { "MAX_PACKET_PIXELS", maxPacketPixels, "pixels of the largest packet the packet_width and packet_height ranges allow" },
  });
  descriptor.shaderFlagSets = { {}, { yfgl09PacketPassFlag } };
  // Like gbp07: the registry-wide sweeps use small maps (brute-force kernels grow with the resolution squared).
  descriptor.sweepTestSettings = { "shadow_map_size=128" };
  descriptor.createPass = newTechniquePass<vtkSLYfgl09Pass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const FrameResult& frame = *context.frame;
    requireSingleSubLight(frame);
    const ShadowMapInputs inputs = shadowMapInputsOf(frame, *context.scene, context.lightIndex);
    const HierarchicalShadowMap mssm = yfgl09Mssm(inputs, frame.parameters);
    std::vector<Yfgl09Pixel> packet;
    const Yfgl09Pixel result = yfgl09ReferencePixel(inputs, mssm, Yfgl09Settings::from(frame.parameters), pixel.x, pixel.y, &recorder, &packet);
    // Yfgl09Test.MatchesTheCpuImplementation: visibility within 1e-3 on pixels without a decision near its
    // boundary (float back-projection and clipping, as gbp07's).
    ProbeOutcome outcome = probeOutcome(result.sample, 1e-3, "yfgl09ReferencePixel (yfgl09/Yfgl09Technique.h): the pixel's packet, double precision");
    outcome.ambiguity = yfgl09Ambiguity(result, packet, frame, pixel);
    return outcome;
  };
  // Back-projection of one shadow-map layer (GBP06, GBP07, Yang et al. 2009): exact for blockers on one plane parallel
  // to the light; where the casters that hide part of the light lie at different depths their back-projections
  // overlap or leave gaps (occluder fusion) and casters hidden from the light's centre are missed.
  descriptor.accuracy = oneLayerSoftShadowContract(BlockerDepthModel::OccluderFusion, 0.05);
  return descriptor;
}

namespace
{

const std::array<glm::ivec2, 4> cellCorners = { glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(1, 1), glm::ivec2(0, 1) };

struct Cells
{
  glm::ivec2 lo{ 0 };
  glm::ivec2 hi{ 0 };
};

// Eq. 3's [z_pmin, z_pmax] over the samples of the cells [firstCell, lastCell]: the comparison depths (with
// receiver-plane bias) of the receivers whose kernels share a cell with them; false when none does.
bool comparisonRangeOverCells(const std::vector<ContourReceiver*>& receivers, int mapSize, glm::ivec2 firstCell,
  glm::ivec2 lastCell, glm::dvec2& comparison)
{
  const int last = mapSize - 1;
  const glm::ivec2 lo = glm::clamp(firstCell, glm::ivec2(0), glm::ivec2(last));
  const glm::ivec2 hi = glm::clamp(lastCell + 1, glm::ivec2(0), glm::ivec2(last));
  comparison = { 1e300, -1e300 };
  bool shared = false;
  for (const ContourReceiver* receiver : receivers)
  {
    const glm::ivec2 sharedLo = glm::max(firstCell, receiver->firstCell());
    const glm::ivec2 sharedHi = glm::min(lastCell, receiver->lastCell());
    if (sharedLo.x <= sharedHi.x && sharedLo.y <= sharedHi.y)
    {
      shared = true;
      const glm::dvec2 range = receiver->geometry.comparisonDepthRange(lo, hi, receiver->bias);
      comparison = { std::min(comparison.x, range.x), std::max(comparison.y, range.y) };
    }
  }
  return shared;
}

// One traversal (Alg. 2 + Alg. 3) for a set of receivers: a packet (pass 1), or a single pixel (pass 2).
// `recorder` (a probe's, optional): the nodes visited (decisions prefixed `name`), the Eq. 3 statuses read and,
// for receiver `probed`, its light centre and every contour edge extracted, with the area it integrated.
class PacketTraversal
{
public:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  PacketTraversal(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm, std::vector<ContourReceiver*> receivers,
    ProbeRecorder* recorder = nullptr, std::size_t probed = none, std::string name = {})
    : inputs_(inputs)
    , mssm_(mssm)
    , receivers_(std::move(receivers))
    , areas_(receivers_.size(), 0.0)
    , recorder_(probed < receivers_.size() ? recorder : nullptr)
    , probed_(probed)
    , name_(std::move(name))
  {
  }

  // Returns false when a sample's status was null (Eq. 3) or the packet outgrew its budget. By every cell or
  // by Alg. 3 (the hierarchy parameter), as the shader's traverse.
  bool run(const Cells& region, bool hierarchy)
  {
    integrateLightCentres();
    return hierarchy ? traverseMssm(region) : traverseEveryCell(region);
  }

  double area(std::size_t p) const { return areas_[p]; }
  int visitedNodes = 0;
  int contourEdges = 0;
  long packetWork = 0; // loop iterations over the packet's pixels, as the GLSL counts them
  bool caughtNull = false;
  bool budgetExceeded = false;
  // For a probe: the cell whose null status stopped the traversal, and the statuses read (1, 0, null).
  glm::ivec2 nullCell{ 0 };
  int occluderStatuses = 0;
  int freeStatuses = 0;
  int nullStatuses = 0;

private:
  // GBP07's radial integration starts from f(O) A, the light centre's status (the shader's addReceiver).
  void integrateLightCentres()
  {
    if (recorder_)
    {
      recorder_->beginGroup(name_ + ": light centre (radial integration)");
    }
    for (std::size_t p = 0; p < receivers_.size(); ++p)
    {
      const double lightArea = 4.0 * receivers_[p]->lightHalfSize * receivers_[p]->lightHalfSize;
      areas_[p] = receivers_[p]->centreOccluded(inputs_, p == probed_ ? recorder_ : nullptr) ? lightArea : 0.0;
    }
  }

  // Alg. 2's loop over every 2 x 2 block of the extended kernel (hierarchy off, the MSSM-only brute force): a
  // cell no receiver's kernel holds is skipped.
  bool traverseEveryCell(const Cells& region)
  {
    for (int j = region.lo.y; j <= region.hi.y; ++j)
    {
      for (int i = region.lo.x; i <= region.hi.x; ++i)
      {
        ++visitedNodes;
        const bool shared = nodeComparisonRange(0, { i, j });
        recordNode(0, { i, j }, shared ? "leaf: marching squares" : "pruned: no pixel's kernel holds the cell");
        if (shared && !leaf({ i, j }))
        {
          return false;
        }
        if (overBudget())
        {
          return false;
        }
      }
    }
    return true;
  }

  // Alg. 3 through the dual-grid MSSM (§4.2): from the lowest node covering the region (at least 2 x 2 cells)
  // with the same first cell; where that node lies above the MSSM's top level (mssm_levels), from the top level's
  // nodes covering the region, row by row (the shader's traverseMssm).
  bool traverseMssm(const Cells& region)
  {
    const glm::ivec2 extent = region.hi - region.lo + 1;
    int rootLevel = 1;
    while (rootLevel < mssm_.topLevel() && (1 << rootLevel) < std::max(extent.x, extent.y))
    {
      ++rootLevel;
    }
    const int side = 1 << rootLevel;
    const glm::ivec2 roots = (extent + side - 1) / side;
    if (recorder_)
    {
      recorder_->beginGroup(name_ + " (Alg. 3)");
      recorder_->quantity("root_level", rootLevel, "level",
        "§4.2, YFGL09: the lowest MSSM level whose node covers the kernel, its top-left side on the kernel's (at most the top level built)");
      recorder_->quantity("roots", roots.x * roots.y, "nodes",
        "nodes of the root level covering the kernel: 1 unless the kernel is wider than the top level built (mssm_levels)");
    }
    for (int k = 0; k < roots.x * roots.y; ++k)
    {
      if (!traverseRoot(rootLevel, region.lo + side * glm::ivec2(k % roots.x, k / roots.x), region))
      {
        return false;
      }
    }
    return true;
  }

  // Alg. 3 below one root, the node of `rootLevel` whose first cell is `rootCell`, depth first, pruning the nodes of
  // Fig. 6 cases 4 and 5. The path of child indices (2 bits per level) replaces the stack.
  bool traverseRoot(int rootLevel, glm::ivec2 rootCell, const Cells& region)
  {
    ++visitedNodes;
    if (!overlaps(rootLevel, rootCell))
    {
      return true;
    }
    int level = rootLevel; // the level of the node whose children are being examined
    glm::ivec2 origin = rootCell;
    unsigned path = 0;
    int child = 0;
    while (true)
    {
      if (child == 4)
      {
        if (level == rootLevel)
        {
          return true;
        }
        const int index = static_cast<int>((path >> (2 * level)) & 3u);
        origin -= cellCorners[static_cast<std::size_t>(index)] << level;
        ++level;
        child = index + 1;
        continue;
      }
      const glm::ivec2 first = origin + (cellCorners[static_cast<std::size_t>(child)] << (level - 1));
      if (first.x > region.hi.x || first.y > region.hi.y)
      {
        ++child; // outside the kernel: no read
        continue;
      }
      ++visitedNodes;
      if (!overlaps(level - 1, first))
      {
        ++child;
      }
      else if (level - 1 == 0)
      {
        if (!leaf(first))
        {
          return false;
        }
        ++child;
      }
      else
      {
        path = (path & ~(3u << (2 * (level - 1)))) | (static_cast<unsigned>(child) << (2 * (level - 1)));
        origin = first;
        --level;
        child = 0;
      }
      if (overBudget())
      {
        return false;
      }
    }
  }

  bool overBudget()
  {
    budgetExceeded = receivers_.size() > 1 && visitedNodes + packetWork > yfgl09PacketBudget;
    return budgetExceeded;
  }

  bool holdsCell(const ContourReceiver& receiver, glm::ivec2 cell) const
  {
    const glm::ivec2 first = receiver.firstCell();
    const glm::ivec2 last = receiver.lastCell();
    return cell.x >= first.x && cell.y >= first.y && cell.x <= last.x && cell.y <= last.y;
  }

  // A probe's record of the node of `level` whose first cell is `firstCell`: the samples of its cells.
  void recordNode(int level, glm::ivec2 firstCell, const std::string& decision)
  {
    if (!recorder_)
    {
      return;
    }
    const glm::dvec2 range = mssm_.dualNode(level, firstCell);
    const glm::ivec2 last(mssm_.mapSize - 1);
    recorder_->node({ "mssm", level, glm::clamp(firstCell, glm::ivec2(0), last),
      glm::clamp(firstCell + (1 << level), glm::ivec2(0), last), range.x, range.y, name_ + ": " + decision });
  }

  // Eq. 3's [z_pmin, z_pmax] over the samples of the node's cells: the comparison depths of the receivers whose
  // kernels share a cell with the node; false when none does.
  bool nodeComparisonRange(int level, glm::ivec2 firstCell)
  {
    const bool shared = comparisonRangeOverCells(receivers_, mssm_.mapSize, firstCell, firstCell + (1 << level) - 1, nodeComparison_);
    packetWork += static_cast<long>(receivers_.size());
    return shared;
  }

  // Fig. 6: can the node's samples produce an edge? Not when all of them are behind the comparison depths
  // (case 4) or all in front (case 5).
  bool overlaps(int level, glm::ivec2 firstCell)
  {
    if (!nodeComparisonRange(level, firstCell))
    {
      recordNode(level, firstCell, "pruned: no pixel's kernel shares a cell with it");
      return false;
    }
    const glm::dvec2 node = mssm_.dualNode(level, firstCell);
    const bool behind = node.x >= nodeComparison_.y;
    const bool inFront = node.y < nodeComparison_.x;
    recordNode(level, firstCell, behind ? "pruned: every sample behind the pixels (Fig. 6 case 4)"
      : inFront ? "pruned: every sample in front of the pixels (Fig. 6 case 5)"
      : level == 0 ? "leaf: marching squares" : "descend");
    return !(behind || inFront);
  }

  // A probe's record of an Eq. 3 status read (each sample once per traversal).
  void recordStatus(glm::ivec2 sample, double z, int status)
  {
    occluderStatuses += status == 1 ? 1 : 0;
    freeStatuses += status == 0 ? 1 : 0;
    nullStatuses += status < 0 ? 1 : 0;
    if (!recorder_ || !recordedStatuses_.insert({ sample.x, sample.y }).second)
    {
      return;
    }
    const ContourReceiver& probed = *receivers_[probed_];
    const double compared = probed.geometry.tapComparisonDepth(glm::dvec2(sample) + 0.5, probed.bias);
    recorder_->texel({ sample, status == 1 ? "Eq. 3 status 1 (occluder)" : status == 0 ? "Eq. 3 status 0 (free)" : "Eq. 3 status null",
      z, compared, status == 1, 1.0 });
  }

  // Eq. 3 for a corner of `cell` (whose node comparison range is current): 1 / 0 for every receiver outside
  // [z_pmin, z_pmax], else decided by the receivers whose kernels hold the cell, -1 (null) where they disagree.
  int status(glm::ivec2 cell, glm::ivec2 sample, double& depth)
  {
    const int size = mssm_.mapSize;
    depth = 0.0;
    if (sample.x < 0 || sample.y < 0 || sample.x >= size || sample.y >= size)
    {
      return 0;
    }
    const double z = inputs_.shadowMapLinear.at(sample.x, sample.y);
    depth = z;
    // The GPU takes these two decisions in float: record how close they are, as a comparison would.
    for (ContourReceiver* receiver : receivers_)
    {
      receiver->lookup.sample.noteDepthComparison(nodeComparison_.x, z);
      receiver->lookup.sample.noteDepthComparison(nodeComparison_.y, z);
    }
    if (z < nodeComparison_.x)
    {
      recordStatus(sample, z, 1);
      return 1;
    }
    if (z >= nodeComparison_.y)
    {
      recordStatus(sample, z, 0);
      return 0;
    }
    int occluded = 0;
    int sharing = 0;
    for (ContourReceiver* receiver : receivers_)
    {
      if (holdsCell(*receiver, cell))
      {
        double unused = 0.0;
        ++sharing;
        occluded += receiver->occludes(inputs_, sample, unused) ? 1 : 0;
      }
    }
    packetWork += static_cast<long>(receivers_.size());
    const int result = occluded == 0 ? 0 : occluded == sharing ? 1 : -1;
    recordStatus(sample, z, result);
    return result;
  }

  // Marching squares on one dual cell with the packet's statuses; edges integrated for each receiver whose
  // kernel holds the cell.
  bool leaf(glm::ivec2 cell)
  {
    std::array<bool, 4> occluding{};
    std::array<double, 4> depths{};
    for (std::size_t k = 0; k < 4; ++k)
    {
      const int s = status(cell, cell + cellCorners[k], depths[k]);
      if (s < 0)
      {
        caughtNull = true;
        nullCell = cell;
        return false;
      }
      occluding[k] = s == 1;
    }
    std::array<ContourEdge, 2> edges;
    const int count = marchingSquaresEdges(occluding, depths, glm::dvec2(cell) + 0.5, edges);
    for (int e = 0; e < count; ++e)
    {
      const ContourEdge& edge = edges[static_cast<std::size_t>(e)];
      for (std::size_t p = 0; p < receivers_.size(); ++p)
      {
        if (holdsCell(*receivers_[p], cell))
        {
          areas_[p] += receivers_[p]->edgeArea(edge.a, edge.depthA, edge.b, edge.depthB, p == probed_ ? recorder_ : nullptr);
        }
      }
      if (recorder_ && !holdsCell(*receivers_[probed_], cell))
      {
        // Extracted for the packet, outside this pixel's kernel: it integrates nothing of it.
        const ContourReceiver& probed = *receivers_[probed_];
        recorder_->contourEdge({ edge.a, edge.b, probed.backProjectToLight(edge.a, edge.depthA),
          probed.backProjectToLight(edge.b, edge.depthB), 0.0 });
      }
    }
    packetWork += static_cast<long>(count) * static_cast<long>(receivers_.size());
    contourEdges += count;
    return true;
  }

  const ShadowMapInputs& inputs_;
  const HierarchicalShadowMap& mssm_;
  std::vector<ContourReceiver*> receivers_;
  std::vector<double> areas_;
  glm::dvec2 nodeComparison_{ 0.0 };
  ProbeRecorder* recorder_ = nullptr;
  std::size_t probed_ = none;
  std::string name_;
  std::set<std::pair<int, int>> recordedStatuses_;
};

double rectangleArea(const TexelRectangle& r)
{
  return r.area();
}

double outsideFraction(const TexelRectangle& kernel, const TexelRectangle& reference)
{
  const glm::ivec2 lo = glm::max(kernel.lo, reference.lo);
  const glm::ivec2 hi = glm::min(kernel.hi, reference.hi);
  const double shared = hi.x < lo.x || hi.y < lo.y ? 0.0 : static_cast<double>(hi.x - lo.x + 1) * (hi.y - lo.y + 1);
  return 1.0 - shared / rectangleArea(kernel);
}

int widthTexels(const TexelRectangle& kernel)
{
  return std::max(kernel.hi.x - kernel.lo.x + 1, kernel.hi.y - kernel.lo.y + 1);
}

// Eq. 6's per-strategy cost of a kernel w texels wide (Q_n = 1; log2 of 1 is 0).
double nodeCost(int width)
{
  return std::log2(static_cast<double>(width)) * width;
}

const char* coherenceDepthName(CoherenceDepth depth)
{
  return depth == CoherenceDepth::Comparison ? "comparison" : depth == CoherenceDepth::Window ? "window" : "linear";
}

const char* const packetSource = "§4.1, Alg. 2, YFGL09 (Yang et al. 2009)";

// A traversal's record for a probe: what it visited and extracted.
void recordTraversal(ProbeRecorder& recorder, const PacketTraversal& traversal, bool completed, const std::string& what)
{
  recorder.quantity(what + "_visited_nodes", traversal.visitedNodes, "nodes",
    "Alg. 3, YFGL09: MSSM nodes (or dual cells, hierarchy off) examined");
  recorder.quantity(what + "_contour_edges", traversal.contourEdges, "edges", "Alg. 2, YFGL09: contour edges extracted");
  recorder.quantity("eq3_occluder_statuses", traversal.occluderStatuses, "count", "Eq. 3, YFGL09: f(s) = 1 (z_s <= z_pmin, or every pixel occluded)");
  recorder.quantity("eq3_free_statuses", traversal.freeStatuses, "count", "Eq. 3, YFGL09: f(s) = 0 (z_pmax <= z_s, or no pixel occluded)");
  recorder.quantity("eq3_null_statuses", traversal.nullStatuses, "count", "Eq. 3, YFGL09: f(s) = null (the pixels disagree)");
  recorder.quantity("packet_work", static_cast<double>(traversal.packetWork), "iterations",
    "ShadowLab: loop iterations over the packet's pixels, against yfgl09PacketBudget with the visited nodes");
  recorder.category(what + "_outcome",
    completed ? std::string("completed")
      : traversal.caughtNull ? "caught null (Eq. 3) at cell (" + std::to_string(traversal.nullCell.x) + ", " +
          std::to_string(traversal.nullCell.y) + "): the packet goes pixel-wise"
      : "over the packet budget: the packet goes pixel-wise",
    "§4.3, YFGL09: a null status met during traversal marks the packet non coherent");
}

// Appends what a packet traversal recorded into a scratch recorder: its nodes and statuses always (they count
// toward the pixel's visited_nodes), its light centre and edges only when the packet computed the pixel.
void appendPacketRecord(ProbeRecorder& to, const ProbeRecord& from, bool computedThePixel)
{
  for (const ProbeNode& node : from.nodes)
  {
    to.node(node);
  }
  to.record().droppedNodes += from.droppedNodes;
  for (const ProbeTexel& texel : from.texels)
  {
    if (computedThePixel || texel.role.rfind("Eq. 3", 0) == 0)
    {
      to.texel(texel);
    }
  }
  to.record().droppedTexels += from.droppedTexels;
  if (!computedThePixel)
  {
    return;
  }
  to.record().quantities.insert(to.record().quantities.end(), from.quantities.begin(), from.quantities.end());
  for (const ProbeLightPolygon& polygon : from.lightPolygons)
  {
    to.lightPolygon(polygon);
  }
  for (const ProbeContourEdge& edge : from.contourEdges)
  {
    to.contourEdge(edge);
  }
  to.record().droppedPolygons += from.droppedPolygons;
  to.record().droppedEdges += from.droppedEdges;
}

// The packet after Alg. 1 step 5: every pixel's receiver and result, the penumbra pixels (traversed together)
// and the probe's bookkeeping. `penumbra` points into `receivers`, reserved for the whole packet (a move keeps
// the addresses).
struct Packet
{
  std::vector<ContourReceiver> receivers;
  std::vector<Yfgl09Pixel> results;
  std::vector<ContourReceiver*> penumbra;
  std::vector<std::size_t> penumbraResults; // index in `results` of each penumbra pixel
  ContourReceiver* reference = nullptr;     // k_0 of Eq. 2
  glm::ivec2 referencePixel{ 0 };
  std::size_t probedPenumbra = PacketTraversal::none; // the probed pixel's index in `penumbra`
  std::size_t probedResult = PacketTraversal::none;
  ProbeRecorder* recorder = nullptr; // the probed pixel's steps (optional)
  ProbeRecorder* probe = nullptr;    // the packet's steps: `recorder` when the probed pixel is in its penumbra
};

// Alg. 1 step 5 for every pixel of the packet whose first pixel is `origin`: its kernel and lit / umbra class;
// the penumbra pixels form the packet, with the reference pixel of Eq. 2 (k_0: the packet's centre pixel, else
// its first penumbra pixel). The shader's computePixelKernels.
Packet computePixelKernels(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, glm::ivec2 origin, ProbeRecorder* recorder,
  glm::ivec2 probed)
{
  const int px = origin.x;
  const int py = origin.y;
  Packet packet;
  packet.recorder = recorder;
  packet.receivers.reserve(static_cast<std::size_t>(settings.packetWidth * settings.packetHeight));
  for (int y = py; y < std::min(py + settings.packetHeight, inputs.position.height); ++y)
  {
    for (int x = px; x < std::min(px + settings.packetWidth, inputs.position.width); ++x)
    {
      const bool isProbed = recorder != nullptr && glm::ivec2(x, y) == probed;
      packet.receivers.push_back(prepareContourReceiver(inputs, settings.receiver, mssm, x, y, isProbed ? recorder : nullptr));
      ContourReceiver& receiver = packet.receivers.back();
      Yfgl09Pixel result;
      result.pixel = { x, y };
      result.kernelTexels = receiver.kernelTexels;
      result.packetClass = receiver.lookup.sample.evaluated ? PacketClass::Trivial : PacketClass::NotTested;
      packet.probedResult = isProbed ? packet.results.size() : packet.probedResult;
      packet.results.push_back(result);
      if (receiver.classification == BackprojectionClass::Penumbra)
      {
        packet.probedPenumbra = isProbed ? packet.penumbra.size() : packet.probedPenumbra;
        packet.penumbra.push_back(&receiver);
        packet.penumbraResults.push_back(packet.results.size() - 1);
        if (x == px + settings.packetWidth / 2 && y == py + settings.packetHeight / 2)
        {
          packet.reference = &receiver;
          packet.referencePixel = { x, y };
        }
      }
    }
  }
  SL_CHECK_MSG(recorder == nullptr || packet.probedResult != PacketTraversal::none, "pixel ", probed.x, ",", probed.y,
    " lies outside the packet at ", px, ",", py);
  packet.probe = packet.probedPenumbra != PacketTraversal::none ? recorder : nullptr;
  if (!packet.reference && !packet.penumbra.empty())
  {
    packet.reference = packet.penumbra.front();
    packet.referencePixel = packet.results[packet.penumbraResults.front()].pixel;
  }
  if (recorder)
  {
    recorder->beginGroup("packet (§4.1, Alg. 2)");
    recorder->quantity("packet_origin", glm::dvec2(origin), "pixels", "§4.1, YFGL09: packets of w x h pixels from the image's corner");
    recorder->quantity("packet_size", glm::dvec2(settings.packetWidth, settings.packetHeight), "pixels", "§4.1, YFGL09: w x h");
    recorder->quantity("packet_penumbra_pixels", static_cast<double>(packet.penumbra.size()), "pixels",
      "Alg. 1 step 5, YFGL09: the packet's pixels neither lit nor umbra, traversed together");
    recorder->category("packet_membership", packet.probe ? "penumbra: computed with the packet" : "lit or umbra: no traversal",
      "Alg. 1 step 5, YFGL09");
  }
  return packet;
}

// Every pixel of the packet as the frame holds it, and the probed pixel's buffers.
std::vector<Yfgl09Pixel> finishPacket(Packet& packet)
{
  std::vector<Yfgl09Pixel>& results = packet.results;
  for (std::size_t p = 0; p < packet.receivers.size(); ++p)
  {
    results[p].sample = packet.receivers[p].lookup.sample;
    results[p].kernelEdgeMargin = packet.receivers[p].kernelEdgeMargin;
    results[p].decisionMargin = packet.receivers[p].decisionMargin;
  }
  if (ProbeRecorder* const recorder = packet.recorder)
  {
    const Yfgl09Pixel& result = results[packet.probedResult];
    recorder->beginGroup("the pixel's buffers");
    if (packet.probe == nullptr)
    {
      recorder->quantity("coherence", result.coherence, "", "Eq. 2, YFGL09: 0, the pixel is in no packet's traversal");
      recorder->quantity("divergence_probability", result.divergenceProbability, "", "Eq. 5, YFGL09: 0, no prediction");
    }
    recorder->category("packet_class", static_cast<int>(result.packetClass), packetClassLabel(result.packetClass),
      "§4.3, Alg. 1 steps 5-8, YFGL09; ShadowLab: the packet_class buffer's code (PacketClass)");
    recorder->quantity("visited_nodes", result.visitedNodes, "nodes",
      "Fig. 8, YFGL09: the pixel's share of its packet's traversal plus its own");
    recorder->quantity("contour_edges", result.contourEdges, "edges", "Alg. 2, YFGL09: edges of the traversal that computed the pixel");
    recorder->quantity("visibility", result.sample.visibility, "",
      packet.probe == nullptr ? decisionSourceOf(packet.receivers[packet.probedResult].classification)
                              : "GBP07 / YFGL09: V = clamp(1 - (f(O) A + sum of s_e |L beyond e|) / A, 0, 1)");
  }
  return std::move(results);
}

// Alg. 2's extended kernel with what §4.3 and Eq. 6 read of the packet.
struct PacketKernel
{
  TexelRectangle kernel;       // the bounding box of the pixels' kernels
  TexelRectangle samples;      // the samples those kernels read (plus one ring): Eq. 4's kernel range
  Cells region;                // the dual cells traversed
  glm::dvec2 comparison{ 0.0 }; // the packet's depth range (§4.3: its pixels' comparison depths)
  double pixelCost = 0.0;      // Eq. 6's denominator
};

// Alg. 2 "construct an extended kernel for the packet" (the shader's constructPacketKernel).
PacketKernel constructPacketKernel(const Packet& packet, const Yfgl09Settings& settings)
{
  PacketKernel packetKernel;
  TexelRectangle kernel = packet.penumbra.front()->kernel;
  TexelRectangle samples = packet.penumbra.front()->samples;
  for (const ContourReceiver* receiver : packet.penumbra)
  {
    kernel = { glm::min(kernel.lo, receiver->kernel.lo), glm::max(kernel.hi, receiver->kernel.hi) };
    samples = { glm::min(samples.lo, receiver->samples.lo), glm::max(samples.hi, receiver->samples.hi) };
  }
  packetKernel.kernel = kernel;
  packetKernel.samples = samples;
  packetKernel.region = { kernel.lo - 1, kernel.hi };
  glm::dvec2 comparison(1e300, -1e300);
  double pixelCost = 0.0;
  for (const ContourReceiver* receiver : packet.penumbra)
  {
    const double own = receiver->geometry.d - receiver->bias;
    comparison = { std::min(comparison.x, own), std::max(comparison.y, own) };
    const int w = widthTexels(receiver->kernel);
    pixelCost += nodeCost(w) + (settings.edgeCost + settings.visibilityCost) * w;
  }
  packetKernel.comparison = comparison;
  packetKernel.pixelCost = pixelCost;
  return packetKernel;
}

// Eq. 2: max_i |k_i \ k_0| / |k_i|, reported (the shader's kernelCoherence).
double kernelCoherence(const Packet& packet)
{
  double coherence = 0.0;
  for (const ContourReceiver* receiver : packet.penumbra)
  {
    coherence = std::max(coherence, outsideFraction(receiver->kernel, packet.reference->kernel));
  }
  return coherence;
}

// What Alg. 1 step 6 decided for the packet, with the figures its buffers report.
struct PacketPrediction
{
  double coherence = 0.0;  // Eq. 2
  double divergence = 0.0; // P_d, Eq. 5
  PacketClass packetClass = PacketClass::Coherent;
};

// Alg. 1 step 6 (§4.3): a packet of more than one penumbra pixel goes pixel-wise when its contours likely
// diverge (Eq. 4-5: P_d > T_d) or when Eq. 6 prefers the pixels; a packet of one pixel is coherent. The
// shader's classifyPacket.
PacketPrediction classifyPacket(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, const Packet& packet, const PacketKernel& packetKernel)
{
  PacketPrediction prediction;
  ProbeRecorder* const probe = packet.probe;
  if (packet.penumbra.size() <= 1)
  {
    if (probe)
    {
      probe->beginGroup("coherence prediction (§4.3)");
      probe->quantity("coherence", prediction.coherence, "", "Eq. 2, YFGL09: 0, a packet of one penumbra pixel");
      probe->quantity("divergence_probability", prediction.divergence, "", "Eq. 5, YFGL09: 0, a packet of one penumbra pixel is coherent");
      probe->category("prediction", "coherent: one penumbra pixel", "§4.3, YFGL09");
    }
    return prediction;
  }
  prediction.coherence = kernelCoherence(packet);
  glm::dvec2 comparison = packetKernel.comparison;
  glm::dvec2 kernelRange = mssm.range(packetKernel.samples.lo, packetKernel.samples.hi);
  if (settings.coherenceDepth == CoherenceDepth::Comparison)
  {
    comparisonRangeOverCells(packet.penumbra, mssm.mapSize, packetKernel.region.lo, packetKernel.region.hi, comparison);
  }
  else if (settings.coherenceDepth == CoherenceDepth::Window)
  {
    const LightView& view = inputs.lightView;
    comparison = { view.windowDepth(comparison.x), view.windowDepth(comparison.y) };
    kernelRange = { view.windowDepth(kernelRange.x), view.windowDepth(kernelRange.y) };
  }
  const double overlap = std::max(std::min(comparison.y, kernelRange.y) - std::max(comparison.x, kernelRange.x), 0.0);
  const double nullProbability = kernelRange.y > kernelRange.x ? overlap / (kernelRange.y - kernelRange.x) : 0.0; // Eq. 4
  const int packetKernelWidth = widthTexels(packetKernel.kernel);
  prediction.divergence = 1.0 - std::pow(1.0 - nullProbability, static_cast<double>(packetKernelWidth) * packetKernelWidth); // Eq. 5
  const double packetPixels = settings.paperPacketCost ? settings.packetWidth * settings.packetHeight : static_cast<double>(packet.penumbra.size());
  const double packetCost = nodeCost(packetKernelWidth) + (settings.edgeCost + settings.visibilityCost * packetPixels) * packetKernelWidth; // Eq. 6
  const bool divergent = settings.divergenceTest && prediction.divergence > settings.divergenceThreshold;
  const bool costly = settings.costTest && packetCost > packetKernel.pixelCost;
  if (divergent || costly)
  {
    prediction.packetClass = PacketClass::NonCoherent;
  }
  if (probe)
  {
    const std::string depthUnit = settings.coherenceDepth == CoherenceDepth::Window ? "window depth" : "linear depth";
    probe->beginGroup("coherence prediction (§4.3)");
    probe->quantity("reference_pixel", glm::dvec2(packet.referencePixel), "pixels", "Eq. 2, YFGL09: k_0, the packet's centre pixel's kernel");
    probe->quantity("coherence", prediction.coherence, "", "Eq. 2, YFGL09: max_i |k_i \\ k_0| / |k_i|");
    probe->category("coherence_depth", coherenceDepthName(settings.coherenceDepth), "§4.3, YFGL09 (issue 13: which depths Eq. 4 compares)");
    probe->quantity("packet_depth_range", comparison, depthUnit, "§4.3, YFGL09: [z_pmin, z_pmax] of the packet");
    probe->quantity("kernel_depth_range", kernelRange, depthUnit, "§4.3, YFGL09: the packet kernel's MSSM range");
    probe->quantity("null_probability", nullProbability, "", "Eq. 4, YFGL09: P_null, the overlap of the two ranges over the kernel's");
    probe->quantity("packet_kernel_width", packetKernelWidth, "texels", "Eq. 5, YFGL09: n, the packet kernel's width");
    probe->quantity("divergence_probability", prediction.divergence, "", "Eq. 5, YFGL09: P_d = 1 - (1 - P_null)^(n^2)");
    probe->quantity("divergence_threshold", settings.divergenceThreshold, "", "§4.3, YFGL09: T_d");
    probe->quantity("packet_cost", packetCost, "node visits", "Eq. 6, YFGL09: n log2 n + (Q_e + Q_v w h) n, Q_n = 1");
    probe->quantity("pixel_cost", packetKernel.pixelCost, "node visits", "Eq. 6, YFGL09: the sum over the pixels of n_i log2 n_i + (Q_e + Q_v) n_i");
    probe->category("prediction", divergent ? "non-coherent: P_d > T_d" : costly ? "non-coherent: Eq. 6 prefers pixels"
      : "coherent", "§4.3, Eq. 5-6, YFGL09");
  }
  return prediction;
}

// A probe's record of the packet kernel and of its pixels' kernels.
void recordPacketKernels(ProbeRecorder& probe, const Packet& packet, const PacketKernel& packetKernel, PacketClass packetClass)
{
  probe.kernel({ "packet", glm::dvec2(packetKernel.kernel.lo), glm::dvec2(packetKernel.kernel.hi + 1), packetClassLabel(packetClass),
    packetSource });
  for (std::size_t p = 0; p < packet.penumbra.size(); ++p)
  {
    const glm::ivec2 pixel = packet.results[packet.penumbraResults[p]].pixel;
    probe.kernel({ "packet pixel kernel", glm::dvec2(packet.penumbra[p]->kernel.lo), glm::dvec2(packet.penumbra[p]->kernel.hi + 1),
      "pixel " + std::to_string(pixel.x) + "," + std::to_string(pixel.y), "Eq. 1, YFGL09" });
  }
}

// What Alg. 1 step 7 leaves for step 8: each pixel's share of the packet's visited nodes, and the occluded
// areas of a completed traversal (empty otherwise).
struct CoherentPacket
{
  PacketClass packetClass = PacketClass::Coherent;
  double visitedShare = 0.0;
  std::vector<double> areas;
};

// Alg. 1 step 7: the packet's traversal over its extended kernel; its pixels' visibilities when it completes.
// A null status (Eq. 3, §4.3: a misclassified packet is "caught during the packet contour extraction") or the
// packet budget leave them to step 8. The shader's evaluateCoherentPacket.
CoherentPacket evaluateCoherentPacket(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, Packet& packet, const Cells& region)
{
  CoherentPacket outcome;
  const std::size_t count = packet.penumbra.size();
  // A probe's view of the packet's traversal goes through a scratch record: its edges belong to the pixel
  // only if the packet completes.
  ProbeRecorder scratch;
  PacketTraversal traversal(inputs, mssm, packet.penumbra, packet.probe ? &scratch : nullptr, packet.probedPenumbra,
    "packet traversal");
  const bool completed = traversal.run(region, settings.hierarchy);
  if (completed)
  {
    for (std::size_t p = 0; p < count; ++p)
    {
      const double lightArea = 4.0 * packet.penumbra[p]->lightHalfSize * packet.penumbra[p]->lightHalfSize;
      packet.penumbra[p]->lookup.sample.visibility = std::clamp(1.0 - traversal.area(p) / lightArea, 0.0, 1.0);
      packet.results[packet.penumbraResults[p]].contourEdges = traversal.contourEdges;
      outcome.areas.push_back(traversal.area(p));
    }
  }
  else
  {
    outcome.packetClass = traversal.caughtNull ? PacketClass::CaughtNull : PacketClass::OverBudget;
  }
  outcome.visitedShare = static_cast<double>(traversal.visitedNodes) / count;
  if (ProbeRecorder* const probe = packet.probe)
  {
    appendPacketRecord(*probe, scratch.record(), completed);
    probe->beginGroup("packet traversal (Alg. 2, Alg. 3)");
    recordTraversal(*probe, traversal, completed, "packet");
    probe->quantity("packet_visited_share", outcome.visitedShare, "nodes",
      "Fig. 8, YFGL09: the packet's visited nodes / its penumbra pixels, each pixel's share");
  }
  return outcome;
}

// Alg. 1 step 8: each pixel of a packet that step 7 did not compute, alone over its own kernel (the shader's
// pixel pass); every penumbra pixel's buffers.
void evaluateRemainingPixels(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, Packet& packet, const PacketPrediction& prediction, const CoherentPacket& coherent)
{
  for (std::size_t p = 0; p < packet.penumbra.size(); ++p)
  {
    ContourReceiver& receiver = *packet.penumbra[p];
    Yfgl09Pixel& result = packet.results[packet.penumbraResults[p]];
    const double lightArea = 4.0 * receiver.lightHalfSize * receiver.lightHalfSize;
    double visited = coherent.visitedShare;
    double occludedArea = coherent.areas.empty() ? 0.0 : coherent.areas[p];
    const bool isProbed = p == packet.probedPenumbra;
    if (coherent.packetClass != PacketClass::Coherent)
    {
      PacketTraversal traversal(inputs, mssm, { &receiver }, isProbed ? packet.probe : nullptr, 0, "pixel traversal");
      const bool completed = traversal.run({ receiver.firstCell(), receiver.lastCell() }, settings.hierarchy);
      receiver.lookup.sample.visibility = std::clamp(1.0 - traversal.area(0) / lightArea, 0.0, 1.0);
      result.contourEdges = traversal.contourEdges;
      visited += traversal.visitedNodes;
      occludedArea = traversal.area(0);
      if (isProbed && packet.probe)
      {
        packet.probe->beginGroup("pixel traversal (Alg. 1 step 8)");
        recordTraversal(*packet.probe, traversal, completed, "pixel");
      }
    }
    result.visitedNodes = visited;
    result.packetClass = coherent.packetClass;
    result.coherence = prediction.coherence;
    result.divergenceProbability = prediction.divergence;
    if (isProbed && packet.probe)
    {
      packet.probe->beginGroup("radial integration");
      packet.probe->quantity("light_area", lightArea, "world units^2", "GBP07: A, the square light");
      packet.probe->quantity("occluded_area", occludedArea, "world units^2",
        "GBP07 radial integration: f(O) A + sum over the pixel's edges of s_e |L beyond e| (light polygon and edges' signed areas)");
    }
  }
}

// Alg. 1 steps 5-8 for the packet whose first pixel is `origin`: every pixel of it, as the frame holds them.
// `recorder` (optional) records the steps of pixel `probed`, which must lie in the packet. The shader runs
// steps 5-7 in its packet pass's main() and step 8 in its pixel pass, with the same step names.
std::vector<Yfgl09Pixel> evaluatePacket(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, glm::ivec2 origin, ProbeRecorder* recorder,
  glm::ivec2 probed)
{
  Packet packet = computePixelKernels(inputs, mssm, settings, origin, recorder, probed);
  if (packet.penumbra.empty())
  {
    return finishPacket(packet);
  }
  const PacketKernel packetKernel = constructPacketKernel(packet, settings);
  const PacketPrediction prediction = classifyPacket(inputs, mssm, settings, packet, packetKernel);
  if (packet.probe)
  {
    recordPacketKernels(*packet.probe, packet, packetKernel, prediction.packetClass);
  }
  CoherentPacket coherent;
  coherent.packetClass = prediction.packetClass;
  if (prediction.packetClass == PacketClass::Coherent)
  {
    coherent = evaluateCoherentPacket(inputs, mssm, settings, packet, packetKernel.region);
  }
  evaluateRemainingPixels(inputs, mssm, settings, packet, prediction, coherent);
  return finishPacket(packet);
}

} // namespace

std::string packetClassLabel(PacketClass packetClass)
{
  const std::size_t code = static_cast<std::size_t>(packetClass);
  SL_CHECK(code < std::size(packetCategories));
  return packetCategories[code].label;
}

HierarchicalShadowMap yfgl09Mssm(const ShadowMapInputs& inputs, const ParameterValues& values)
{
  const int topLevel = minMaxTopLevel(HsmLayout::DualMssm, inputs.lightView, *inputs.light,
    values.choice("mssm_levels") == "read");
  return HierarchicalShadowMap::buildDual(inputs.shadowMapLinear, static_cast<float>(2.0 * inputs.lightView.farDepth),
    topLevel);
}

Yfgl09Frame yfgl09Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm, const Yfgl09Settings& settings)
{
  SL_CHECK(mssm.layout == HsmLayout::DualMssm);
  const int width = inputs.position.width;
  const int height = inputs.position.height;
  Yfgl09Frame frame;
  for (ImageF* image : { &frame.visibility, &frame.kernelTexels, &frame.coherence, &frame.packetClass,
         &frame.divergenceProbability, &frame.visitedNodes, &frame.contourEdges })
  {
    *image = ImageF(width, height, 1);
  }
  frame.samples.resize(static_cast<std::size_t>(width) * height);
  frame.kernelEdgeMargin.assign(frame.samples.size(), 1e300);
  frame.decisionMargin.assign(frame.samples.size(), 1e300);
  for (int py = 0; py < height; py += settings.packetHeight)
  {
    for (int px = 0; px < width; px += settings.packetWidth)
    {
      for (const Yfgl09Pixel& result : evaluatePacket(inputs, mssm, settings, { px, py }, nullptr, {}))
      {
        const int x = result.pixel.x;
        const int y = result.pixel.y;
        const std::size_t index = static_cast<std::size_t>(y) * width + x;
        frame.samples[index] = result.sample;
        frame.kernelEdgeMargin[index] = result.kernelEdgeMargin;
        frame.decisionMargin[index] = result.decisionMargin;
        frame.visibility.at(x, y) = static_cast<float>(result.sample.visibility);
        frame.kernelTexels.at(x, y) = static_cast<float>(result.kernelTexels);
        frame.coherence.at(x, y) = static_cast<float>(result.coherence);
        frame.packetClass.at(x, y) = static_cast<float>(result.packetClass);
        frame.divergenceProbability.at(x, y) = static_cast<float>(result.divergenceProbability);
        frame.visitedNodes.at(x, y) = static_cast<float>(result.visitedNodes);
        frame.contourEdges.at(x, y) = static_cast<float>(result.contourEdges);
      }
    }
  }
  return frame;
}

Yfgl09Pixel yfgl09ReferencePixel(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm,
  const Yfgl09Settings& settings, int x, int y, ProbeRecorder* recorder, std::vector<Yfgl09Pixel>* packet)
{
  SL_CHECK(mssm.layout == HsmLayout::DualMssm);
  SL_CHECK_MSG(x >= 0 && y >= 0 && x < inputs.position.width && y < inputs.position.height, "pixel ", x, ",", y,
    " outside the image");
  // The frame's packets start at the image's corner (yfgl09Reference).
  const glm::ivec2 origin(x - x % settings.packetWidth, y - y % settings.packetHeight);
  std::vector<Yfgl09Pixel> results = evaluatePacket(inputs, mssm, settings, origin, recorder, { x, y });
  const auto it = std::find_if(results.begin(), results.end(), [&](const Yfgl09Pixel& r) { return r.pixel == glm::ivec2(x, y); });
  SL_CHECK(it != results.end());
  const Yfgl09Pixel pixel = *it;
  if (packet)
  {
    *packet = std::move(results);
  }
  return pixel;
}

} // namespace sl
