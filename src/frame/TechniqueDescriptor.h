// The vocabulary of the technique registry (techniques/Registry.h): adding a technique touches one place.
//
// A technique is described by data: its parameters (bgfx-style table: default, range, unit, doc), the
// light-space structures it needs (the pipeline builds only those), the instrumentation buffers it
// publishes, and how to make its visibility pass. The CLI (`list`, `--set`), the renderer, the outputs
// and the regression suite iterate the registry; nothing else switches on technique names.
#pragma once

#include "core/Error.h"
#include "core/NamedImage.h"
#include "core/Parameters.h"
#include "scene/Scene.h"

#include <vtkSmartPointer.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

class vtkSLTechniquePass;

namespace sl
{

struct FrameResult;   // frame/FrameResult.h
class ProbeRecorder;  // frame/ProbeRecord.h

// What a probe replays one pixel from: the rendered frame (its read-back buffers and light-space exports) and
// the scene it was rendered from.
struct ProbeContext
{
  const FrameResult* frame = nullptr;
  const Scene* scene = nullptr;
  int lightIndex = 0;
};

// The CPU twin's answer for the probed pixel, and how far the GPU's may legitimately differ from it.
struct ProbeOutcome
{
  bool evaluated = false;   // the pixel reached a shadow test (false: decided without one, e.g. facing away)
  double visibility = 0.0;  // the twin's
  // The largest |GPU - twin| the technique's GPU-CPU tests accept on an unambiguous pixel; a twin that knows how many
  // of its decisions sit at a float-rounding boundary may widen it for this pixel (reference-sm: 1/K per such sample).
  double tolerance = 0.0;
  // Non-empty when a decision of this pixel lies within float rounding of its boundary (the tests' ambiguity
  // thresholds): GPU and twin may then differ by more than `tolerance`, and the probe says why instead of failing.
  std::string ambiguity;
  std::string twin;         // what was replayed, e.g. "pcssReference (PcssTechnique.h), double precision"
};

struct LightSpaceStructure; // structures/LightSpaceStructure.h

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
  // Categorical buffers: the shaders' name of each category, upper case, one per label (code = index). The
  // shader preamble defines `<NAME>_<IDENTIFIER> <code>` (e.g. CLASSIFICATION_PENUMBRA_OVER_BUDGET 4), which
  // the shader writes; the CPU mirror's enum is the one declaration both are made from.
  std::vector<std::string> categoryIdentifiers;
  // The category that marks a pixel whose value was cut short (a GL's cap on loop iterations, a budget) and
  // is therefore not exact, or -1. The pipeline counts such pixels (`cut_short_pixels` in stats.json), render
  // and bench warn about them, and sub-light combination keeps the mark from any sub-light.
  int cutShortCode = -1;
  // Not a render target: the technique's pass reads it back itself (vtkSLTechniquePass::CollectPassBuffers),
  // with as many components as it needs (e.g. dcs's light_sample_mask, N/16 of them); no OUT_ location. The pass
  // may leave out one that its parameters do not ask for (the doc says when).
  bool fromPass = false;
  // A continuous buffer whose value at or above this marks a pixel the method cannot be trusted at (esm's
  // bias_gain): the pipeline counts such pixels (technique statistic "<name>_flagged_pixels") and render warns
  // with `flagWarning`, which says why and what to change. Infinity: the buffer flags nothing.
  double flagAtOrAbove = std::numeric_limits<double>::infinity();
  std::string flagWarning;
  // Where the buffer has a value (core/NamedImage.h); the heat maps draw the other pixels grey.
  BufferDomain domain = BufferDomain::Covered;
};

// `spec` declared to hold values only where a shadow test ran (BufferDomain::ShadowTested): the shader writes 0
// elsewhere, which the heat maps must not show as a value.
inline BufferSpec onShadowTestedPixels(BufferSpec spec)
{
  spec.domain = BufferDomain::ShadowTested;
  return spec;
}

// An integer the technique's shaders and its C++ share (a loop budget, the bound of an array, the codes of a
// decision the CPU mirror makes too): generated into the shader preamble as `#define <name> <value>`, from the
// constexpr the C++ side uses, so no shader keeps a copy.
struct ShaderConstant
{
  std::string name; // upper case, e.g. "LOOP_BUDGET"
  int value = 0;
  std::string doc;
};

// One code of a categorical buffer, declared once beside the C++ enum that the CPU twin uses: `value` is the
// code, `identifier` the enumerator's name in upper case (the shader's <BUFFER>_<IDENTIFIER> define), `label`
// what heat-map keys and stats show.
template <class Enum>
struct Category
{
  Enum value;
  const char* identifier;
  const char* label;
  bool cutShort = false; // BufferSpec::cutShortCode
};

// A categorical buffer whose codes are `categories`, listed in code order (SL_CHECKed: code i is entry i).
template <class Enum, std::size_t Count>
BufferSpec categoricalBuffer(std::string name, std::string doc, const Category<Enum> (&categories)[Count],
  SubLightCombine combine = SubLightCombine::Mean)
{
  BufferSpec spec{ std::move(name), "", std::move(doc), BufferKind::Categorical, {}, combine };
  for (std::size_t code = 0; code < Count; ++code)
  {
    SL_CHECK_MSG(static_cast<std::size_t>(categories[code].value) == code, "buffer ", spec.name, ": category ",
      categories[code].identifier, " is listed out of code order");
    spec.categoryIdentifiers.push_back(categories[code].identifier);
    spec.categoryLabels.push_back(categories[code].label);
    if (categories[code].cutShort)
    {
      SL_CHECK_MSG(spec.cutShortCode < 0, "buffer ", spec.name, ": more than one cut-short category");
      spec.cutShortCode = static_cast<int>(code);
    }
  }
  return spec;
}

// Multisampled rendering (Schwarz and Stamminger 2008 §7): a `samples`x multisampled G-buffer, the technique evaluated
// once per pixel from the first sample (the single-sampled G-buffer targets hold sample 0), and a custom resolve in
// which a sample whose view depth d_s is within `depthTolerance` (relative: |d_s - s_z| <= tau s_z) of the pixel's
// s_z takes the pixel's visibility and any other the visibility of the pixel or 4-neighbour whose s_z is closest
// (passes/vtkSLMsaaResolvePass.h).
// What a technique's typed settings ask of the light-space structures it needs beyond the structures' own
// parameters, so a structure never reads a technique's parameter by name (structures/LightSpaceStructure.h).
struct LightSpaceRequest
{
  // The width of the filter it applies to the shadow map (pcf's kernel, the moment techniques' prefilter box): the
  // focus leaves ceil(width / 2) + 1 texels of margin for it (structures/shadowmap/ShadowMapStructure.h).
  // `filterParameter` names the setting in the error when that margin leaves no texel for the receivers; empty:
  // no filter (one texel of margin).
  std::string filterParameter;
  double filterTexels = 0.0;
  // c of the moment map's exp(c z_n) channel (esm_exponent, Annen et al. 2008); 0: the channel holds 1.
  double momentExponent = 0.0;
  // true: no range query it makes of the N-buffers or the dual-grid MSSM is wider than Eq. 1's initial kernel of the
  // farthest receiver (Yang et al. 2009; the blocker search region of VSSM Alg. 1), plus its ring, so those are built
  // only up to that level (hsm_levels / mssm_levels = read; structures/hsm/HsmStructure.h). Wider queries stay exact.
  bool minMaxQueriesWithinNearPlaneKernel = false;
};

struct MultisampleSettings
{
  int samples = 1; // 1 (off) or 4
  double depthTolerance = 0.0;
};

// Where a technique is approximate by design, and how close it must come to the ray-traced truth elsewhere (issue
// 27): the differential test (differential/Differential.h) holds every technique to its contract on random scenes,
// and the pipeline publishes, per pixel, which declared approximation applies (buffer `approximation`, counted as
// `approximate_pixels` in stats.json), so a user sees where a value may legitimately be off.
enum class ReferenceModel
{
  AreaLight,  // the fraction of the whole light visible (the ray tracer's area integral)
  LightCentre // the single ray to the light's centre: techniques that sample an area light from its centre
};

// One approximation a technique makes by design (its paper's, or the project's documented choice).
struct Approximation
{
  std::string name; // the label of its code in `approximation`, e.g. "average blocker depth"
  std::string doc;  // when it applies, as the marking rule decides it per pixel
};

// What a technique's marking rule reads: the rendered frame (its read-back buffers and light-space exports) and the
// scene and light it was rendered from.
struct ApproximationContext
{
  const FrameResult* frame = nullptr;
  const Scene* scene = nullptr;
  int lightIndex = 0;
};

struct AccuracyContract
{
  ReferenceModel reference = ReferenceModel::AreaLight;
  // The largest |V - V_ref| accepted on a pixel no flag marks, before the reference's own noise (and, for
  // techniques that publish `visibility_stderr`, their own) is added.
  double tolerance = 0.0;
  std::vector<Approximation> approximations;
  // Techniques that estimate the visible fraction from N light samples: N for a frame's parameters (unset: not
  // sampled). Their estimate of a pixel whose true visibility is v spreads by sqrt(v (1 - v) / N) even where their
  // own visibility_stderr, computed from their estimate, is 0 (all N samples on one side of a thin penumbra).
  std::function<int(const ParameterValues& values)> lightSampleCount;
  // Sets codes(x, y) = 1 + the index of the declared approximation that applies at the pixel, 0 where none does
  // (`codes` arrives W x H x 1, all 0). Unset: the technique declares no approximation.
  std::function<void(const ApproximationContext& context, ImageF& codes)> markApproximations;
};

struct TechniqueDescriptor
{
  std::string name;    // CLI name: "pcf"
  std::string title;   // "Percentage-closer filtering"
  std::string paper;   // "Reeves et al. 1987; survey (Scherzer et al. 2011) §6"
  std::vector<ParameterSpec> parameters;
  // The light-space structures its shader reads (each structure's header, e.g. structures/sat/SatStructure.h):
  // the pipeline builds them (and what they are built from) and binds them to the technique's shader.
  std::vector<const LightSpaceStructure*> lightStructures;
  // Whether a frame rendered with `values` needs `structure`, one of lightStructures (e.g. ss08 reads its
  // microrects only with micro_occluder=microrect); unset: every one. The pipeline builds, binds and exports
  // only the needed ones (structuresFor); `list` shows all of lightStructures.
  std::function<bool(const LightSpaceStructure& structure, const ParameterValues& values)> structureNeeded;
  std::vector<BufferSpec> buffers; // published in addition to the common ones (visibility, position, ...)
  std::vector<LightType> supportedLights;
  std::vector<LightShape> supportedAreaShapes = { LightShape::Square, LightShape::Disk }; // for area lights
  // The shadow map must hold every caster that hides any part of an area light, not only its centre
  // (soft-shadow techniques): the focus stage widens the light frustum by the light's footprint.
  bool coversLightArea = false;
  // shadow_map_size = auto never chooses more than this (lightspace/AutomaticMapSize.h caps every technique at 2048,
  // the fixed default before auto); the back-projection techniques, ss08, reference-sm and temporal keep 1024, their
  // fixed default, past which their per-texel work outgrows the frame (and llvmpipe's loop cap cuts kernels short).
  int largestAutomaticMapSize = 2048;
  // An object-space technique (shadow volumes, penumbra wedges) draws the scene's geometry itself: the pipeline
  // gives its pass the casters with welded connectivity (FrameResources::weldedCasters) and the G-buffer's
  // depth-stencil texture to test against and write stencil into; it may export vtkPolyData
  // (vtkSLTechniquePass::CollectObjectSpaceExports, written as <name>.vtp).
  bool drawsSceneGeometry = false;
  // With drawsSceneGeometry: perforated casters (alpha textures) are left out of FrameResources::weldedCasters, because
  // the technique shadows them itself, by soft textured shadow volumes (Forest et al. 2009: S-triangles go through STSV).
  bool perforatedCastersByStsv = false;
  // Settings the registry-wide test sweeps (regression baselines, the NaN/inf sweep) add, to keep a brute-force
  // technique's cost on llvmpipe bounded (e.g. a smaller shadow map). Empty for most techniques.
  std::vector<std::string> sweepTestSettings;
  // Defined in the shader preamble besides the outputs (OUT_<BUFFER>), the categories and the enumeration
  // parameters; tests/unit/ShaderContractTest.cpp checks that the shaders keep no copy of them.
  std::vector<ShaderConstant> shaderConstants;
  // The flag sets (`#define FLAG`) the technique's pass compiles its fragment shader with, one program each
  // ({} = the generated preamble alone); the shader-contract test assembles every one.
  std::vector<std::vector<std::string>> shaderFlagSets = { {} };
  std::function<vtkSmartPointer<vtkSLTechniquePass>()> createPass;
  // Where the technique is approximate by design and the tolerance it meets elsewhere (AccuracyContract). Declared
  // in the technique's own folder, beside the rest of its descriptor.
  AccuracyContract accuracy;
  // `shadowlab probe` (issue 15): replays the technique's CPU twin on one pixel of a rendered frame, recording
  // every step into `recorder`. Every registered technique has one (tests/render/ProbeTest.cpp asserts it);
  // it throws InputError for a setting it cannot replay.
  std::function<ProbeOutcome(const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder)> probe;
  // Multi-view shadow maps (Yang et al. 2009 §5): a technique with an integer parameter "sublights" = S is run
  // once per sub-light of the square area light split S x S (its own focus, shadow map and light-space
  // structures each); buffers combine per BufferSpec::subLightCombine and `sublight_visibility` holds the S^2
  // sub-light visibilities. See subLightsParameter() (techniques/SoftShadowSupport.h).
  bool hasSubLights() const { return findParameter("sublights") != nullptr; }
  // S, the sub-lights per side a frame with `values` renders (1 without `sublights`): the one place it is read.
  int subLightsPerSide(const ParameterValues& values) const { return hasSubLights() ? values.getInt("sublights") : 1; }
  // The multisampling a frame rendered with the given values asks for; unset: none (samples = 1).
  std::function<MultisampleSettings(const ParameterValues& values)> multisample;
  MultisampleSettings multisampleFor(const ParameterValues& values) const
  {
    return multisample ? multisample(values) : MultisampleSettings{};
  }

  // What a frame with the given values asks of its light-space structures, from its typed settings; unset: nothing.
  std::function<LightSpaceRequest(const ParameterValues& values)> lightSpaceRequest;
  LightSpaceRequest lightSpaceRequestFor(const ParameterValues& values) const
  {
    return lightSpaceRequest ? lightSpaceRequest(values) : LightSpaceRequest{};
  }

  const ParameterSpec* findParameter(const std::string& parameterName) const;
  // Appends parameters declared elsewhere (a structure's, a shared set) after those listed so far.
  void addParameters(const std::vector<ParameterSpec>& specs) { parameters.insert(parameters.end(), specs.begin(), specs.end()); }
  // Every parameter at its default.
  ParameterValues defaultParameters() const { return ParameterValues(name, parameters); }
  bool needs(const LightSpaceStructure& structure) const;
  // The light-space structures a frame with `values` builds: lightStructures filtered by structureNeeded.
  std::vector<const LightSpaceStructure*> structuresFor(const ParameterValues& values) const;
  // Names of the technique pass's targets in output-location order: "visibility", then the buffers.
  std::vector<std::string> outputNames() const;
  // The light's type is supported, and for an area light its shape.
  bool supports(const Light& light) const;
};

// A descriptor with its identity set, the rest at the defaults above: every technique's descriptor starts here.
TechniqueDescriptor describeTechnique(std::string name, std::string title, std::string paper);

// createPass for a pass class: `descriptor.createPass = newTechniquePass<vtkSLPcfPass>;` (instantiated where the
// pass's header is included).
template <class Pass>
vtkSmartPointer<vtkSLTechniquePass> newTechniquePass()
{
  return vtkSmartPointer<Pass>::New();
}

} // namespace sl
