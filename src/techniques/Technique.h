// The technique registry's vocabulary (STYLE.md, "Adding a technique touches one place").
//
// A technique is described by data: its parameters (bgfx-style table: default, range, unit, doc), the
// light-space structures it needs (the pipeline builds only those), the instrumentation buffers it
// publishes, and how to make its visibility pass. The CLI (`list`, `--set`), the renderer, the outputs
// and the regression suite iterate the registry; nothing else switches on technique names.
#pragma once

#include "scene/Scene.h"

#include <vtkSmartPointer.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

class vtkSLTechniquePass;

namespace sl
{

struct ParameterSpec
{
  std::string name;
  double defaultValue = 0.0;
  double minValue = 0.0;
  double maxValue = 0.0;
  std::string unit;                 // "texels", "", ...
  std::string doc;                  // one line, cites the paper where it comes from
  std::vector<std::string> choices; // non-empty: an enumeration, the value is the index of the choice
  bool integer = false;             // integer-valued numeric parameter
};

// Light-space structures a technique can ask for. Each is built by its own pass, only when needed, and
// exported in light_space.vti.
enum class LightStructure
{
  ShadowMap, // linear depth (R32F) + hardware depth (D32F) from the light's centre, focused (survey §4.1)
  MomentMap, // (z, z^2, exp(c z_n)) of the shadow map, prefiltered by a box blur or mip-mapped (survey §6)
  SummedAreaTable, // of the shadow map's (z, z^2): float (centred) or 32-bit integer (survey §6.4)
  HierarchicalShadowMap, // min-max depth pyramid, mip-map or N-buffers (VSSM §6.1)
  DualMultiScaleShadowMap, // the MSSM on the dual grid of 2 x 2 sample blocks (Yang et al. 2009 §4.2)
};
std::string lightStructureName(LightStructure structure);

enum class BufferKind
{
  Continuous, // heat map with a sequential colour map
  Signed,     // diverging colour map about 0
  Categorical // integer classes with labels
};

// How a buffer of a technique with sub-lights (parameter `sublights`, Yang et al. 2009 §5) combines the
// S x S sub-light frames: visibility and continuous values are averaged, work counters summed, categorical
// buffers kept from the first sub-light (they cannot be averaged).
enum class SubLightCombine
{
  Mean,
  Sum,
  First
};

struct BufferSpec
{
  std::string name; // array name in buffers.vti, e.g. "kernel_texels"
  std::string unit;
  std::string doc;
  BufferKind kind = BufferKind::Continuous;
  std::vector<std::string> categoryLabels;
  SubLightCombine subLightCombine = SubLightCombine::Mean;
};

struct TechniqueDescriptor
{
  std::string name;    // CLI name: "pcf"
  std::string title;   // "Percentage-closer filtering"
  std::string paper;   // "Reeves et al. 1987; survey (Scherzer et al. 2011) §6"
  std::vector<ParameterSpec> parameters;
  std::vector<LightStructure> lightStructures;
  std::vector<BufferSpec> buffers; // published in addition to the common ones (visibility, position, ...)
  std::vector<LightType> supportedLights;
  std::vector<LightShape> supportedAreaShapes = { LightShape::Square, LightShape::Disk }; // for area lights
  // The shadow map must hold every caster that hides any part of an area light, not only its centre
  // (soft-shadow techniques): the focus stage widens the light frustum by the light's footprint.
  bool coversLightArea = false;
  // Settings the registry-wide test sweeps (regression baselines, the NaN/inf sweep) add, to keep a brute-force
  // technique's cost on llvmpipe bounded (e.g. a smaller shadow map). Empty for most techniques.
  std::vector<std::string> sweepTestSettings;
  std::function<vtkSmartPointer<vtkSLTechniquePass>()> createPass;
  // Multi-view shadow maps (Yang et al. 2009 §5): a technique with an integer parameter "sublights" = S is run
  // once per sub-light of the square area light split S x S (its own focus, shadow map and light-space
  // structures each); buffers combine per BufferSpec::subLightCombine and `sublight_visibility` holds the S^2
  // sub-light visibilities. See subLightsParameter() (techniques/SoftShadowSupport.h).
  bool hasSubLights() const { return findParameter("sublights") != nullptr; }

  const ParameterSpec* findParameter(const std::string& parameterName) const;
  bool needs(LightStructure structure) const;
  // The light's type is supported, and for an area light its shape.
  bool supports(const Light& light) const;
};

// Parameter values resolved against a descriptor: every parameter has a value, all within range.
class ParameterValues
{
public:
  ParameterValues() = default;
  explicit ParameterValues(const TechniqueDescriptor& descriptor);

  double get(const std::string& name) const;        // SL_CHECKs the name exists
  int getInt(const std::string& name) const;
  const std::string& choice(const std::string& name) const; // enumeration's chosen name
  // Parses "key=value" (a number, or a choice name for enumerations, or true/false for 0..1 integers).
  // Throws InputError naming the technique, key and value when unknown or out of range.
  void set(const std::string& assignment);
  void set(const std::string& key, double value);
  const std::map<std::string, double>& values() const { return values_; }
  const TechniqueDescriptor& descriptor() const { return *descriptor_; }

private:
  const TechniqueDescriptor* descriptor_ = nullptr;
  std::map<std::string, double> values_;
};

const std::vector<TechniqueDescriptor>& techniqueRegistry();
// Throws InputError listing the available techniques when `name` is unknown.
const TechniqueDescriptor& findTechnique(const std::string& name);

} // namespace sl
