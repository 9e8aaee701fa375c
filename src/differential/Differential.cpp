#include "differential/Differential.h"

#include "core/Error.h"
#include "frame/Approximations.h"
#include "frame/FrameResult.h"
#include "pipeline/ShadowRenderer.h"
#include "reference/ReferenceRenderer.h"
#include "scene/RandomScenes.h"
#include "scene/Scene.h"
#include "scene/WeldedMesh.h"
#include "techniques/Registry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

namespace sl
{
namespace
{

// The drawn shadow-map size: the technique's default halved `halvings` times, within the parameter's range. Where
// the default is `auto`, halvings 0 keeps it and 1..3 give 1024, 512 and 256 (the sizes the earlier fixed default,
// 2048, halved to).
std::optional<std::string> mapSizeSetting(const TechniqueDescriptor& technique, int halvings)
{
  const ParameterSpec* spec = technique.findParameter("shadow_map_size");
  if (!spec || (isAutomaticValue(*spec, spec->defaultValue) && halvings == 0))
  {
    return std::nullopt;
  }
  const double largest = isAutomaticValue(*spec, spec->defaultValue) ? 2048.0 : spec->defaultValue;
  const double size = std::max(spec->minValue, std::floor(largest / static_cast<double>(1 << halvings)));
  return "shadow_map_size=" + std::to_string(static_cast<long long>(size));
}

struct SeedReferences
{
  FrameResult gbuffer;
  ReferenceResult area;
  ReferenceResult centre;
  std::optional<ReferenceResult> multisample; // made when a multisampled frame first needs it
};

// The single ray to the centre: the reference of the same scene under a point light there.
ReferenceResult centreReference(const FrameResult& gbuffer, const Scene& scene)
{
  Light centre = scene.lights.front();
  if (centre.type == LightType::Area)
  {
    centre.type = LightType::Point;
  }
  ReferenceInputs inputs = referenceInputsOf(gbuffer, scene, 0);
  inputs.light = &centre;
  ReferenceSettings settings;
  settings.samples = 1;
  ReferenceResult result = renderReference(inputs, settings);
  result.standardError = ImageF(result.visibility.width, result.visibility.height, 1, 0.0f);
  return result;
}

void compare(const FrameResult& frame, const ReferenceResult& reference, bool centreEdges, double tolerance,
  double sigmas, ConfigurationOutcome& outcome)
{
  const AccuracyContract& contract = frame.descriptor->accuracy;
  const int sampleCount = contract.lightSampleCount ? contract.lightSampleCount(frame.parameters) : 0;
  const ImageF& visibility = frame.find("visibility")->image;
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& receives = frame.find("receives_shadows")->image;
  const NamedImage* approximation = frame.find(kApproximationBuffer);
  const NamedImage* ownError = frame.find("visibility_stderr");
  struct CutShort
  {
    const ImageF* buffer;
    float code;
    std::string label;
  };
  std::vector<CutShort> cutShort;
  for (const BufferSpec& spec : frame.descriptor->buffers)
  {
    if (spec.cutShortCode >= 0 && frame.find(spec.name))
    {
      cutShort.push_back(
        { &frame.find(spec.name)->image, static_cast<float>(spec.cutShortCode), "cut short: " + spec.name });
    }
  }
  const ImageF& truth = reference.visibility;
  SL_CHECK(truth.width == visibility.width && truth.height == visibility.height);
  double worstExcess = 0.0;
  for (int y = 0; y < visibility.height; ++y)
  {
    for (int x = 0; x < visibility.width; ++x)
    {
      if (coverage.at(x, y) <= 0.5f || receives.at(x, y) <= 0.5f)
      {
        continue;
      }
      ++outcome.pixels;
      const float approximationCode = approximation ? approximation->image.at(x, y) : 0.0f;
      const std::string* flag = nullptr;
      if (approximationCode > 0.0f)
      {
        const std::size_t index = static_cast<std::size_t>(approximationCode) - 1;
        SL_CHECK_MSG(index < contract.approximations.size(), frame.technique, ": approximation code ",
          approximationCode, " declares no approximation");
        flag = &contract.approximations[index].name;
      }
      for (const CutShort& cut : cutShort)
      {
        if (!flag && cut.buffer->at(x, y) == cut.code)
        {
          flag = &cut.label;
        }
      }
      const bool flagged = flag != nullptr;
      FlagCount* flagCount = flagged ? &outcome.flaggedBy[*flag] : nullptr;
      if (flagCount)
      {
        ++outcome.flagged;
        ++flagCount->flagged;
      }
      const double difference = std::abs(static_cast<double>(visibility.at(x, y)) - truth.at(x, y));
      // A sampling technique's own noise: its published stderr, or the spread of N samples about the true value,
      // whichever is larger (its stderr is 0 where all its samples agree).
      const double truthValue = truth.at(x, y);
      const double ownNoise = std::max(ownError ? static_cast<double>(ownError->image.at(x, y)) : 0.0,
        sampleCount > 0 ? std::sqrt(truthValue * (1.0 - truthValue) / sampleCount) : 0.0);
      const double allowed = tolerance + sigmas * (reference.standardError.at(x, y) + ownNoise);
      if (difference <= allowed)
      {
        continue;
      }
      if (flagged)
      {
        ++outcome.flaggedMisses;
        ++flagCount->beyondTolerance;
        continue;
      }
      bool edge = false;
      if (centreEdges)
      {
        const int neighbours[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
        for (const auto& step : neighbours)
        {
          const int nx = x + step[0];
          const int ny = y + step[1];
          edge |= nx >= 0 && ny >= 0 && nx < truth.width && ny < truth.height && coverage.at(nx, ny) > 0.5f &&
            truth.at(nx, ny) != truth.at(x, y);
        }
      }
      if (edge)
      {
        ++outcome.ambiguous;
        continue;
      }
      ++outcome.failures;
      if (difference - allowed > worstExcess)
      {
        worstExcess = difference - allowed;
        outcome.worst = PixelMiss{ x, y, visibility.at(x, y), truth.at(x, y), allowed };
      }
    }
  }
}

std::string choiceLabel(const std::string& choice) { return choice; }

// Second-depth shadow maps store the casters' back faces, which an open caster lacks
// (src/techniques/hard/README.md, "Common to hard and pcf": casters must be closed): the choice does not apply to a
// scene with an open caster.
std::string closedCastersRequirement(const std::string& choice, const Scene& scene)
{
  if (choice != "caster_faces=back")
  {
    return "";
  }
  for (const WeldedMesh& caster : weldCasters(scene))
  {
    if (caster.boundaryEdgeCount() > 0)
    {
      return "caster_faces=back needs closed casters; " + scene.objects.at(caster.objectIndex).name + " is open";
    }
  }
  return "";
}

} // namespace

std::vector<std::string> enumeratedChoices(const TechniqueDescriptor& technique)
{
  std::vector<std::string> choices = { "default" };
  for (const ParameterSpec& spec : technique.parameters)
  {
    for (std::size_t index = 0; index < spec.choices.size(); ++index)
    {
      if (static_cast<double>(index) != spec.defaultValue)
      {
        choices.push_back(spec.name + "=" + spec.choices[index]);
      }
    }
  }
  return choices;
}

std::string reproduceCommand(std::uint64_t seed, const std::string& technique, const std::string& choice, int maxSide)
{
  return "shadowlab differential --seeds " + std::to_string(seed) + " -t " + technique + " --choice " + choice +
    " --max-side " + std::to_string(maxSide);
}

namespace
{

// DifferentialOptions::seedsPerChoice: which (seed index, technique, choice) run besides the defaults. Whether a
// configuration can run is known before any GL (the technique takes the scene's light, the choice applies to its
// casters), so a choice is given a seed where it compares nothing only when no seed would do.
std::set<std::tuple<std::size_t, std::string, std::string>> rotatedChoiceSeeds(const DifferentialOptions& options,
  const std::vector<const TechniqueDescriptor*>& techniques)
{
  std::vector<Scene> scenes;
  for (const std::uint64_t seed : options.seeds)
  {
    scenes.push_back(parseScene(randomScene(seed, options.maxSide).json, "differential seed " + std::to_string(seed),
      std::filesystem::current_path()));
  }
  std::set<std::tuple<std::size_t, std::string, std::string>> selected;
  for (const TechniqueDescriptor* technique : techniques)
  {
    const std::vector<std::string> choices =
      options.choice.empty() ? enumeratedChoices(*technique) : std::vector<std::string>{ options.choice };
    for (std::size_t choiceIndex = 0; choiceIndex < choices.size(); ++choiceIndex)
    {
      int taken = 0;
      for (std::size_t step = 0; step < scenes.size() && taken < options.seedsPerChoice; ++step)
      {
        const std::size_t seedIndex = (choiceIndex + step) % scenes.size();
        const Scene& scene = scenes[seedIndex];
        if (technique->supports(scene.lights.front()) && closedCastersRequirement(choices[choiceIndex], scene).empty())
        {
          selected.insert({ seedIndex, technique->name, choices[choiceIndex] });
          ++taken;
        }
      }
      if (taken == 0 && !scenes.empty())
      {
        // No seed it applies to: its own seed, whose outcome then says why (unsupported light, open casters).
        selected.insert({ choiceIndex % scenes.size(), technique->name, choices[choiceIndex] });
      }
    }
  }
  return selected;
}

} // namespace

std::vector<ConfigurationOutcome> runDifferential(ShadowRenderer& renderer, const DifferentialOptions& options,
  const std::function<void(const ConfigurationOutcome&)>& report)
{
  std::vector<const TechniqueDescriptor*> techniques;
  if (options.techniques.empty())
  {
    for (const TechniqueDescriptor& technique : techniqueRegistry())
    {
      techniques.push_back(&technique);
    }
  }
  for (const std::string& name : options.techniques)
  {
    techniques.push_back(&findTechnique(name));
  }
  if (!options.choice.empty())
  {
    for (const TechniqueDescriptor* technique : techniques)
    {
      const std::vector<std::string> choices = enumeratedChoices(*technique);
      if (std::find(choices.begin(), choices.end(), options.choice) == choices.end())
      {
        throw InputError("--choice " + options.choice + ": not a choice of " + technique->name +
          " (\"default\" or key=value of an enumerated parameter other than its default)");
      }
    }
  }

  if (options.seedsPerChoice < 0)
  {
    throw InputError("seeds per choice " + std::to_string(options.seedsPerChoice) + ": must be >= 0 (0 = every seed)");
  }
  const std::set<std::tuple<std::size_t, std::string, std::string>> selected =
    options.seedsPerChoice > 0 ? rotatedChoiceSeeds(options, techniques) : std::set<std::tuple<std::size_t, std::string, std::string>>{};

  std::vector<ConfigurationOutcome> outcomes;
  for (std::size_t seedIndex = 0; seedIndex < options.seeds.size(); ++seedIndex)
  {
    const std::uint64_t seed = options.seeds[seedIndex];
    const RandomScene random = randomScene(seed, options.maxSide);
    const std::string label = "differential seed " + std::to_string(seed);
    if (!options.sceneDir.empty())
    {
      const std::filesystem::path directory = options.sceneDir / ("seed-" + std::to_string(seed));
      std::filesystem::create_directories(directory);
      std::ofstream(directory / "scene.json") << random.json;
    }
    const Scene scene = parseScene(random.json, label, std::filesystem::current_path());

    SeedReferences references;
    RenderRequest gbufferRequest;
    // The G-buffer is the same for every technique, but the renderer checks the light against the request's: take
    // one that supports it (with none, every configuration of the seed is unsupported and nothing is rendered).
    const auto supporting = std::find_if(techniques.begin(), techniques.end(),
      [&](const TechniqueDescriptor* technique) { return technique->supports(scene.lights.front()); });
    gbufferRequest.technique = (supporting != techniques.end() ? *supporting : techniques.front())->name;
    gbufferRequest.gbufferOnly = true;
    ReferenceSettings areaSettings;
    areaSettings.samples = options.referenceSamples;
    areaSettings.seed = seed;
    if (supporting != techniques.end())
    {
      references.gbuffer = renderer.render(scene, gbufferRequest);
      references.area = renderReference(referenceInputsOf(references.gbuffer, scene, 0), areaSettings);
      references.centre = centreReference(references.gbuffer, scene);
    }

    for (const TechniqueDescriptor* technique : techniques)
    {
      const std::vector<std::string> choices =
        options.choice.empty() ? enumeratedChoices(*technique) : std::vector<std::string>{ options.choice };
      for (const std::string& choice : choices)
      {
        if (options.seedsPerChoice > 0 && choice != "default" && !selected.count({ seedIndex, technique->name, choice }))
        {
          continue;
        }
        ConfigurationOutcome outcome;
        outcome.seed = seed;
        outcome.technique = technique->name;
        outcome.choice = choiceLabel(choice);
        outcome.scene = random.summary;
        outcome.command = reproduceCommand(seed, technique->name, choice, options.maxSide);
        outcome.supported = technique->supports(scene.lights.front());
        if (choice != "default")
        {
          outcome.settings.push_back(choice);
        }
        if (const std::optional<std::string> mapSize = mapSizeSetting(*technique, random.mapSizeHalvings))
        {
          outcome.settings.push_back(*mapSize);
        }
        outcome.notApplicable = outcome.supported ? closedCastersRequirement(choice, scene) : "";
        if (outcome.supported && outcome.notApplicable.empty())
        {
          const auto start = std::chrono::steady_clock::now();
          try
          {
            RenderRequest request;
            request.technique = technique->name;
            request.settings = outcome.settings;
            const FrameResult frame = renderer.render(scene, request);
            const AccuracyContract& contract = technique->accuracy;
            const ReferenceModel model = options.referenceModelOverride.value_or(contract.reference);
            const ReferenceResult* reference = &references.area;
            if (model == ReferenceModel::LightCentre)
            {
              reference = &references.centre;
            }
            else if (technique->multisampleFor(frame.parameters).samples > 1)
            {
              if (!references.multisample)
              {
                std::vector<ReferenceInputs> perSample;
                const std::vector<FrameResult> samples =
                  renderer.renderSampleGBuffers(scene, gbufferRequest, technique->multisampleFor(frame.parameters).samples);
                for (const FrameResult& sample : samples)
                {
                  perSample.push_back(referenceInputsOf(sample, scene, 0));
                }
                references.multisample = renderMultisampleReference(perSample, areaSettings);
              }
              reference = &*references.multisample;
            }
            compare(frame, *reference, model == ReferenceModel::LightCentre, contract.tolerance,
              options.noiseSigmas, outcome);
          }
          catch (const InputError& error)
          {
            outcome.notApplicable = error.what();
          }
          catch (const std::exception& error)
          {
            outcome.error = error.what();
          }
          outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        if (report)
        {
          report(outcome);
        }
        outcomes.push_back(std::move(outcome));
      }
    }
  }
  return outcomes;
}

std::map<std::string, DifferentialTally> tallyByTechnique(const std::vector<ConfigurationOutcome>& outcomes)
{
  std::map<std::string, DifferentialTally> tallies;
  for (const ConfigurationOutcome& outcome : outcomes)
  {
    DifferentialTally& tally = tallies[outcome.technique];
    if (!outcome.supported || !outcome.notApplicable.empty())
    {
      ++tally.unsupported;
      continue;
    }
    ++tally.configurations;
    tally.pixels += outcome.pixels;
    tally.flagged += outcome.flagged;
    tally.flaggedMisses += outcome.flaggedMisses;
    for (const auto& [name, count] : outcome.flaggedBy)
    {
      tally.flaggedBy[name].flagged += count.flagged;
      tally.flaggedBy[name].beyondTolerance += count.beyondTolerance;
    }
    tally.ambiguous += outcome.ambiguous;
    tally.failures += outcome.failures;
    tally.failedConfigurations += outcome.failed() ? 1 : 0;
    tally.seconds += outcome.seconds;
  }
  return tallies;
}

std::string describeFailure(const ConfigurationOutcome& outcome)
{
  std::ostringstream line;
  line << "seed " << outcome.seed << " " << outcome.technique << " " << outcome.choice << ": ";
  if (!outcome.error.empty())
  {
    line << "error: " << outcome.error;
  }
  else
  {
    line << outcome.failures << " of " << outcome.pixels << " pixels beyond the contract (" << outcome.flagged
         << " flagged, " << outcome.ambiguous << " ambiguous)";
    if (outcome.worst)
    {
      line << ", worst at " << outcome.worst->x << "," << outcome.worst->y << ": V " << outcome.worst->visibility
           << ", reference " << outcome.worst->reference << ", allowed " << outcome.worst->allowed;
    }
  }
  line << "; settings";
  for (const std::string& setting : outcome.settings)
  {
    line << " " << setting;
  }
  line << "; scene:" << outcome.scene << "\n    reproduce: " << outcome.command;
  return line.str();
}

} // namespace sl
