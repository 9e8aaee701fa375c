// The randomized differential test of every technique against the ray tracer (issue 27): random scenes
// (scene/RandomScenes.h), every technique and each of its enumerated parameter choices rendered on them, each pixel
// held to the technique's accuracy contract (TechniqueDescriptor::accuracy):
//
//   |V - V_ref| <= tolerance + k (stderr_ref + stderr_own)
//
// on every covered pixel that receives shadows, where V_ref is the Embree reference of the contract's model (the
// whole light, stratified samples, or the single ray to its centre), stderr_ref its published standard error and
// stderr_own the technique's own `visibility_stderr` where it publishes one (sampling techniques). A pixel that
// misses is *flagged* when its `approximation` code or a cut-short code marks it, *ambiguous* when the contract's
// reference is the light's centre and a 4-neighbour's reference differs (the hard edge runs through the pixel's
// footprint: which side the point falls on is a matter of float rounding between the rasteriser and Embree), and a
// *failure* otherwise. `shadowlab differential` runs it (cli/DifferentialCommand.cpp), tests/render/DifferentialTest.cpp
// runs a slice, docs/bench/differential holds the full sweep.
#pragma once

#include "frame/TechniqueDescriptor.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

class ShadowRenderer;

struct DifferentialOptions
{
  std::vector<std::uint64_t> seeds;
  std::vector<std::string> techniques; // empty: every registered one
  std::string choice;                  // empty: every choice; else only "default" or "key=value"
  // 0: every choice on every seed. n > 0: the default on every seed, each other choice on n seeds only, the first n
  // that the technique supports and the choice applies to, taken in rotation from the choice's own place in the seed
  // list, so that the choices spread over the scenes (the test's slice: the product costs too much per case).
  int seedsPerChoice = 0;
  int maxSide = 128;                   // RandomScenes.h
  int referenceSamples = 256;          // stratified, per pixel, for the area-light reference
  double noiseSigmas = 3.0;            // k
  std::filesystem::path sceneDir;      // non-empty: each scene is written to <sceneDir>/seed-<S>/scene.json
  // Tests only: compare with this reference model instead of the contract's (a wrong declaration must fail).
  std::optional<ReferenceModel> referenceModelOverride;
};

struct PixelMiss
{
  int x = 0;
  int y = 0;
  double visibility = 0.0;
  double reference = 0.0;
  double allowed = 0.0;
};

// Pixels one flag excuses: marked (compared pixels it flags) and, of those, beyond the allowance.
struct FlagCount
{
  long long flagged = 0;
  long long beyondTolerance = 0;
};

struct ConfigurationOutcome
{
  std::uint64_t seed = 0;
  std::string technique;
  std::string choice;                 // "default" or "key=value"
  std::vector<std::string> settings;  // everything set: the choice and the drawn shadow-map size
  std::string scene;                  // RandomScene::summary
  bool supported = true;              // false: the technique does not take the scene's light (nothing run)
  // Non-empty: the configuration does not apply to this scene (nothing compared), and why: a choice documented
  // for closed casters only (caster_faces=back, second-depth maps) on a scene with open ones, or settings the
  // technique refuses as incomplete (InputError, e.g. budget_map=image without budget_image).
  std::string notApplicable;
  std::string error;                  // the render threw: its message (counted as a failed configuration)
  int pixels = 0;                     // compared (covered, receiving)
  int flagged = 0;                    // marked by an approximation or cut-short code
  int flaggedMisses = 0;              // of those, beyond the allowance
  // The same split by flag: the declared approximation's name (the pixel's `approximation` code, set by the first of
  // the technique's rules that marks it), else "cut short: <buffer>" for a pixel only a cut-short code marks.
  std::map<std::string, FlagCount> flaggedBy;
  int ambiguous = 0;                  // beyond the allowance on a centre-ray edge (see above)
  int failures = 0;                   // beyond the allowance, unmarked
  std::optional<PixelMiss> worst;     // the failure with the largest excess
  std::string command;                // the one command that reproduces this configuration
  double seconds = 0.0;
  bool failed() const { return !error.empty() || failures > 0; }
};

// "default", then "key=choice" for every enumerated parameter's choices other than its default, in parameter order.
std::vector<std::string> enumeratedChoices(const TechniqueDescriptor& technique);

// `shadowlab differential --seeds S -t T --choice C --max-side M`: reruns one configuration.
std::string reproduceCommand(std::uint64_t seed, const std::string& technique, const std::string& choice, int maxSide);

// Runs every configuration, calling `report` after each; throws InputError for an unknown technique or choice.
std::vector<ConfigurationOutcome> runDifferential(ShadowRenderer& renderer, const DifferentialOptions& options,
  const std::function<void(const ConfigurationOutcome&)>& report = {});

// Per technique: configurations run (supported), pixels, flagged, failures, failed configurations.
struct DifferentialTally
{
  int configurations = 0;
  int unsupported = 0;   // the light (shape or type), or not applicable to the scene (ConfigurationOutcome)
  long long pixels = 0;
  long long flagged = 0;
  long long flaggedMisses = 0;
  std::map<std::string, FlagCount> flaggedBy; // summed over the configurations (ConfigurationOutcome::flaggedBy)
  long long ambiguous = 0;
  long long failures = 0;
  int failedConfigurations = 0;
  double seconds = 0.0;
};
std::map<std::string, DifferentialTally> tallyByTechnique(const std::vector<ConfigurationOutcome>& outcomes);

// One line per failed configuration: seed, technique, choice, counts, the worst pixel and the command.
std::string describeFailure(const ConfigurationOutcome& outcome);

} // namespace sl
