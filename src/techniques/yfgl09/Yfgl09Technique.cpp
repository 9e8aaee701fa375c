#include "techniques/yfgl09/Yfgl09Technique.h"

#include "lightspace/mssm/DualMssmStructure.h"
#include "lightspace/shadowmap/ShadowMapStructure.h"

#include "core/Error.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/backprojection/ContourBackprojection.h"
#include "techniques/backprojection/ContourReceiver.h"
#include "techniques/yfgl09/vtkSLYfgl09Pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

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

TechniqueDescriptor yfgl09Technique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "yfgl09";
  descriptor.title = "Packet-based hierarchical soft shadow mapping (contours, packets, dual-grid MSSM traversal)";
  descriptor.paper = "Yang, Feng, Guennebaud and Liu 2009, §4, Eq. 1-6, Alg. 1-3";
  descriptor.parameters = shadowMapParameters();
  for (ParameterSpec& spec : descriptor.parameters)
  {
    if (spec.name == "shadow_map_size")
    {
      spec.defaultValue = 1024; // the paper's maps; gbp07's default, for like-for-like comparisons
    }
  }
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "kernel_refinements", 2, 0, 4, "iterations", "times the kernel is shrunk to the minimum occluder depth inside it (Eq. 1 with z_occ_min from the MSSM)", {}, true },
    { "packet_width", 3, 1, 4, "pixels", "packet width w (§4.1; 1 x 1 = pixel-wise, the packet optimisation off)", {}, true },
    { "packet_height", 3, 1, 4, "pixels", "packet height h (§4.1)", {}, true },
    { "hierarchy", 1, 0, 1, "", "contour extraction through the dual-grid MSSM (§4.2, Alg. 3) or every dual cell of the kernel (off: the MSSM-only brute force)", { "off", "on" }, true },
    { "coherence_test", 0, 0, 3, "", "which predictions send a packet pixel-wise before its traversal (§4.3): the divergence probability (Eq. 5 > T_d), the cost model (Eq. 6 > 1), both, or none (null statuses still do)", { "both", "divergence", "cost", "off" }, true },
    { "divergence_threshold", 0.8, 0.0, 1.0, "", "T_d of §4.3 (the paper: 0.8)", {}, false },
    { "edge_cost", 4.0, 0.0, 100.0, "", "Q_e of Eq. 6, cost of extracting an edge relative to visiting a node (Q_n = 1)", {}, false },
    { "visibility_cost", 8.0, 0.0, 100.0, "", "Q_v of Eq. 6, cost of back-projecting and integrating an edge for one pixel (Q_n = 1)", {}, false },
    { "packet_cost", 0, 0, 1, "", "Eq. 6's visibility term for the packet: paper = Q_v w h, every pixel of the packet (000 L560-563); penumbra_pixels = Q_v times the packet's penumbra pixels only (trivial pixels integrate nothing)", { "paper", "penumbra_pixels" }, true },
    { "coherence_depth", 0, 0, 2, "", "the depths Eq. 4's P_null compares (§4.3): linear = the packet's pixel depths minus bias against the kernel samples' linear light depths (the text's reading); comparison = the receiver-plane comparison depths over the packet kernel, the range Eq. 3's statuses use; window = the linear reading in the map's window (post-projective, hyperbolic) depth, as a depth buffer stores it", { "linear", "comparison", "window" }, true },
    subLightsParameter(),
  });
  descriptor.lightStructures = { &shadowMapStructure(), &dualMssmStructure() };
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
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLYfgl09Pass>::New()); };
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
class PacketTraversal
{
public:
  PacketTraversal(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm, std::vector<ContourReceiver*> receivers)
    : inputs_(inputs)
    , mssm_(mssm)
    , receivers_(std::move(receivers))
    , areas_(receivers_.size(), 0.0)
  {
  }

  // Returns false when a sample's status was null (Eq. 3) or the packet outgrew its budget.
  bool run(const Cells& region, bool hierarchy)
  {
    for (std::size_t p = 0; p < receivers_.size(); ++p)
    {
      const double lightArea = 4.0 * receivers_[p]->lightHalfSize * receivers_[p]->lightHalfSize;
      areas_[p] = receivers_[p]->centreOccluded(inputs_) ? lightArea : 0.0;
    }
    if (!hierarchy)
    {
      for (int j = region.lo.y; j <= region.hi.y; ++j)
      {
        for (int i = region.lo.x; i <= region.hi.x; ++i)
        {
          ++visitedNodes;
          if (nodeComparisonRange(0, { i, j }) && !leaf({ i, j }))
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
    // Alg. 3: the lowest node covering the region (at least 2 x 2 cells) with the same first cell, then depth
    // first. The path of child indices (2 bits per level) replaces the stack.
    const glm::ivec2 extent = region.hi - region.lo + 1;
    int rootLevel = 1;
    while ((1 << rootLevel) < std::max(extent.x, extent.y))
    {
      ++rootLevel;
    }
    ++visitedNodes;
    if (!overlaps(rootLevel, region.lo))
    {
      return true;
    }
    int level = rootLevel; // the level of the node whose children are being examined
    glm::ivec2 origin = region.lo;
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

  double area(std::size_t p) const { return areas_[p]; }
  int visitedNodes = 0;
  int contourEdges = 0;
  long packetWork = 0; // loop iterations over the packet's pixels, as the GLSL counts them
  bool caughtNull = false;
  bool budgetExceeded = false;

private:
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
      return false;
    }
    const glm::dvec2 node = mssm_.dualNode(level, firstCell);
    return !(node.x >= nodeComparison_.y || node.y < nodeComparison_.x);
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
      return 1;
    }
    if (z >= nodeComparison_.y)
    {
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
    return occluded == 0 ? 0 : occluded == sharing ? 1 : -1;
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
          areas_[p] += receivers_[p]->edgeArea(edge.a, edge.depthA, edge.b, edge.depthB);
        }
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

} // namespace

Yfgl09Frame yfgl09Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& mssm, const ParameterValues& values)
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

  const int packetWidth = values.getInt("packet_width");
  const int packetHeight = values.getInt("packet_height");
  const bool hierarchy = values.choice("hierarchy") == "on";
  const std::string& test = values.choice("coherence_test");
  const bool divergenceTest = test == "both" || test == "divergence";
  const bool costTest = test == "both" || test == "cost";
  const double divergenceThreshold = values.get("divergence_threshold");
  const double edgeCost = values.get("edge_cost");
  const double visibilityCost = values.get("visibility_cost");
  const bool paperPacketCost = values.choice("packet_cost") == "paper";
  const std::string& coherenceDepth = values.choice("coherence_depth");

  for (int py = 0; py < height; py += packetHeight)
  {
    for (int px = 0; px < width; px += packetWidth)
    {
      // Alg. 1 step 5 for every pixel of the packet; the penumbra ones form the packet.
      std::vector<ContourReceiver> receivers;
      std::vector<glm::ivec2> pixels;
      std::vector<ContourReceiver*> penumbra;
      std::vector<glm::ivec2> penumbraPixels;
      receivers.reserve(static_cast<std::size_t>(packetWidth * packetHeight));
      ContourReceiver* reference = nullptr;
      for (int y = py; y < std::min(py + packetHeight, height); ++y)
      {
        for (int x = px; x < std::min(px + packetWidth, width); ++x)
        {
          receivers.push_back(prepareContourReceiver(inputs, values, mssm, x, y));
          pixels.emplace_back(x, y);
          ContourReceiver& receiver = receivers.back();
          frame.kernelTexels.at(x, y) = static_cast<float>(receiver.kernelTexels);
          frame.packetClass.at(x, y) = static_cast<float>(receiver.lookup.sample.evaluated ? PacketClass::Trivial : PacketClass::NotTested);
          if (receiver.classification == BackprojectionClass::Penumbra)
          {
            penumbra.push_back(&receiver);
            penumbraPixels.emplace_back(x, y);
            if (x == px + packetWidth / 2 && y == py + packetHeight / 2)
            {
              reference = &receiver;
            }
          }
        }
      }
      const auto finish = [&]() {
        for (std::size_t p = 0; p < receivers.size(); ++p)
        {
          const std::size_t index = static_cast<std::size_t>(pixels[p].y) * width + pixels[p].x;
          frame.samples[index] = receivers[p].lookup.sample;
          frame.kernelEdgeMargin[index] = receivers[p].kernelEdgeMargin;
          frame.decisionMargin[index] = receivers[p].decisionMargin;
          frame.visibility.at(pixels[p].x, pixels[p].y) = static_cast<float>(receivers[p].lookup.sample.visibility);
        }
      };
      if (penumbra.empty())
      {
        finish();
        continue;
      }
      const std::size_t count = penumbra.size();
      reference = reference ? reference : penumbra.front();

      // The packet kernel: the bounding box of its pixels' kernels (Alg. 2), as texels, samples and cells.
      TexelRectangle kernel = penumbra.front()->kernel;
      TexelRectangle samples = penumbra.front()->samples;
      for (const ContourReceiver* receiver : penumbra)
      {
        kernel = { glm::min(kernel.lo, receiver->kernel.lo), glm::max(kernel.hi, receiver->kernel.hi) };
        samples = { glm::min(samples.lo, receiver->samples.lo), glm::max(samples.hi, receiver->samples.hi) };
      }
      const Cells region{ kernel.lo - 1, kernel.hi };
      // The packet's depth range (§4.3: its pixels' comparison depths).
      glm::dvec2 comparison(1e300, -1e300);
      double pixelCost = 0.0;
      for (const ContourReceiver* receiver : penumbra)
      {
        const double own = receiver->geometry.d - receiver->bias;
        comparison = { std::min(comparison.x, own), std::max(comparison.y, own) };
        const int w = widthTexels(receiver->kernel);
        pixelCost += nodeCost(w) + (edgeCost + visibilityCost) * w;
      }

      // §4.3: Eq. 2 (reported), Eq. 4-5 and Eq. 6 (deciding), for packets of more than one pixel.
      double coherence = 0.0;
      double divergence = 0.0;
      PacketClass packetClass = PacketClass::Coherent;
      if (count > 1)
      {
        for (const ContourReceiver* receiver : penumbra)
        {
          coherence = std::max(coherence, outsideFraction(receiver->kernel, reference->kernel));
        }
        glm::dvec2 kernelRange = mssm.range(samples.lo, samples.hi);
        if (coherenceDepth == "comparison")
        {
          comparisonRangeOverCells(penumbra, mssm.mapSize, region.lo, region.hi, comparison);
        }
        else if (coherenceDepth == "window")
        {
          const LightView& view = inputs.lightView;
          comparison = { view.windowDepth(comparison.x), view.windowDepth(comparison.y) };
          kernelRange = { view.windowDepth(kernelRange.x), view.windowDepth(kernelRange.y) };
        }
        const double overlap = std::max(std::min(comparison.y, kernelRange.y) - std::max(comparison.x, kernelRange.x), 0.0);
        const double nullProbability = kernelRange.y > kernelRange.x ? overlap / (kernelRange.y - kernelRange.x) : 0.0; // Eq. 4
        const int packetKernelWidth = widthTexels(kernel);
        divergence = 1.0 - std::pow(1.0 - nullProbability, static_cast<double>(packetKernelWidth) * packetKernelWidth); // Eq. 5
        const double packetPixels = paperPacketCost ? packetWidth * packetHeight : static_cast<double>(count);
        const double packetCost = nodeCost(packetKernelWidth) + (edgeCost + visibilityCost * packetPixels) * packetKernelWidth; // Eq. 6
        if ((divergenceTest && divergence > divergenceThreshold) || (costTest && packetCost > pixelCost))
        {
          packetClass = PacketClass::NonCoherent;
        }
      }
      double packetVisitedShare = 0.0;
      if (packetClass == PacketClass::Coherent)
      {
        PacketTraversal traversal(inputs, mssm, penumbra);
        if (traversal.run(region, hierarchy))
        {
          for (std::size_t p = 0; p < count; ++p)
          {
            const double lightArea = 4.0 * penumbra[p]->lightHalfSize * penumbra[p]->lightHalfSize;
            penumbra[p]->lookup.sample.visibility = std::clamp(1.0 - traversal.area(p) / lightArea, 0.0, 1.0);
            frame.contourEdges.at(penumbraPixels[p].x, penumbraPixels[p].y) = static_cast<float>(traversal.contourEdges);
          }
        }
        else
        {
          packetClass = traversal.caughtNull ? PacketClass::CaughtNull : PacketClass::OverBudget;
        }
        packetVisitedShare = static_cast<double>(traversal.visitedNodes) / count;
      }
      for (std::size_t p = 0; p < count; ++p)
      {
        const glm::ivec2 pixel = penumbraPixels[p];
        double visited = packetVisitedShare;
        if (packetClass != PacketClass::Coherent)
        {
          // Step 8: the pixel alone, over its own kernel.
          PacketTraversal traversal(inputs, mssm, { penumbra[p] });
          traversal.run({ penumbra[p]->firstCell(), penumbra[p]->lastCell() }, hierarchy);
          const double lightArea = 4.0 * penumbra[p]->lightHalfSize * penumbra[p]->lightHalfSize;
          penumbra[p]->lookup.sample.visibility = std::clamp(1.0 - traversal.area(0) / lightArea, 0.0, 1.0);
          frame.contourEdges.at(pixel.x, pixel.y) = static_cast<float>(traversal.contourEdges);
          visited += traversal.visitedNodes;
        }
        frame.visitedNodes.at(pixel.x, pixel.y) = static_cast<float>(visited);
        frame.packetClass.at(pixel.x, pixel.y) = static_cast<float>(packetClass);
        frame.coherence.at(pixel.x, pixel.y) = static_cast<float>(coherence);
        frame.divergenceProbability.at(pixel.x, pixel.y) = static_cast<float>(divergence);
      }
      finish();
    }
  }
  return frame;
}

} // namespace sl
