// The light-space structure registry (structures/LightSpaceStructure.h), without GL: the registry is a build
// order (a structure after what it is built from), the build closure a technique gets, every technique declares
// the parameters of the structures it builds the way the structures declare them, the stage names the builds
// time are unambiguous, and each structure's typed settings read what its parameters say.
#include "core/Error.h"
#include "lightspace/HierarchicalShadowMap.h"
#include "structures/LightSpaceStructure.h"
#include "structures/lightsamples/LightSampleSetStructure.h"
#include "structures/hsm/HsmStructure.h"
#include "structures/moments/MomentMapStructure.h"
#include "structures/mssm/DualMssmStructure.h"
#include "structures/sat/SatStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace sl
{
namespace
{

std::vector<std::string> namesOf(const std::vector<const LightSpaceStructure*>& structures)
{
  std::vector<std::string> names;
  for (const LightSpaceStructure* structure : structures)
  {
    names.push_back(structure->name);
  }
  return names;
}

std::size_t registryIndex(const LightSpaceStructure* structure)
{
  const auto& registry = lightSpaceStructureRegistry();
  return static_cast<std::size_t>(std::find(registry.begin(), registry.end(), structure) - registry.begin());
}

// The stage names a structure's build passes time (vtkSLStagePass::GetStageName, the names in stats.json).
std::vector<std::string> buildStageNames(const LightSpaceStructure& structure)
{
  std::vector<std::string> names;
  for (const auto& pass : structure.createBuildPasses())
  {
    names.push_back(pass->GetStageName());
  }
  return names;
}

TEST(LightSpaceStructureRegistry, NamesAreUniqueAndEachStructureComesAfterWhatItIsBuiltFrom)
{
  const auto& registry = lightSpaceStructureRegistry();
  ASSERT_FALSE(registry.empty());
  EXPECT_EQ(registry.front(), &shadowMapStructure()) << "every other structure is built from the shadow map";
  std::set<std::string> names;
  std::set<std::string> parameterNames;
  for (std::size_t index = 0; index < registry.size(); ++index)
  {
    const LightSpaceStructure& structure = *registry[index];
    EXPECT_FALSE(structure.name.empty());
    EXPECT_TRUE(names.insert(structure.name).second) << "duplicate structure " << structure.name;
    EXPECT_FALSE(structure.doc.empty()) << structure.name;
    EXPECT_TRUE(structure.createBuildPasses && structure.exportImages && structure.gpuBytes &&
      structure.shaderDefines && structure.bind)
      << structure.name << " lacks one of its build, export, memory, defines or binding";
    EXPECT_FALSE(buildStageNames(structure).empty()) << structure.name << " has no build pass";
    for (const LightSpaceStructure* source : structure.builtFrom)
    {
      ASSERT_NE(source, nullptr) << structure.name;
      EXPECT_LT(registryIndex(source), index)
        << structure.name << " is built from " << source->name << ", which is not earlier in the registry";
    }
    // The light-sample set lives on the light itself (structures/lightsamples): no light view, nothing to build from.
    if (&structure != &shadowMapStructure() && &structure != &lightSampleSetStructure())
    {
      EXPECT_NE(std::find(structure.builtFrom.begin(), structure.builtFrom.end(), &shadowMapStructure()),
        structure.builtFrom.end())
        << structure.name << " is not built from the shadow map (every build reads its light view)";
    }
    // Two structures declaring one name would fight over a technique's single value of it.
    for (const ParameterSpec& spec : structure.parameters)
    {
      EXPECT_TRUE(parameterNames.insert(spec.name).second) << spec.name << " is declared by two structures";
      if (!isAutomaticValue(spec, spec.defaultValue))
      {
        EXPECT_LE(spec.minValue, spec.defaultValue) << structure.name << "." << spec.name;
        EXPECT_LE(spec.defaultValue, spec.maxValue) << structure.name << "." << spec.name;
      }
      EXPECT_FALSE(spec.doc.empty()) << structure.name << "." << spec.name;
      if (!spec.choices.empty())
      {
        EXPECT_EQ(spec.minValue, 0.0) << structure.name << "." << spec.name;
        EXPECT_EQ(spec.maxValue, static_cast<double>(spec.choices.size() - 1)) << structure.name << "." << spec.name;
      }
    }
  }
}

TEST(LightSpaceStructureRegistry, BuildDependenciesAreTheClosureInRegistryOrderEachOnce)
{
  using Names = std::vector<std::string>;
  const LightSpaceStructure* shadowMap = &shadowMapStructure();
  const LightSpaceStructure* moments = &momentMapStructure();
  const LightSpaceStructure* table = &summedAreaTableStructure();
  const LightSpaceStructure* hsm = &hierarchicalShadowMapStructure();
  const LightSpaceStructure* dual = &dualMssmStructure();

  EXPECT_TRUE(withBuildDependencies({}).empty());
  EXPECT_EQ(namesOf(withBuildDependencies({ shadowMap })), (Names{ "shadow_map" }));
  EXPECT_EQ(namesOf(withBuildDependencies({ table })), (Names{ "shadow_map", "summed_area_table" }));
  EXPECT_EQ(namesOf(withBuildDependencies({ dual })), (Names{ "shadow_map", "dual_mssm" }));
  // Listed out of order and twice: registry order, each once.
  EXPECT_EQ(namesOf(withBuildDependencies({ hsm, table, shadowMap, table })),
    (Names{ "shadow_map", "summed_area_table", "hierarchical_shadow_map" }));
  EXPECT_EQ(namesOf(withBuildDependencies({ dual, moments })), (Names{ "shadow_map", "moment_map", "dual_mssm" }));
  EXPECT_EQ(withBuildDependencies(lightSpaceStructureRegistry()), lightSpaceStructureRegistry());

  // Against the definition, for every subset of the registry: `needed` plus what it is built from, transitively,
  // in registry order.
  const auto& registry = lightSpaceStructureRegistry();
  ASSERT_LT(registry.size(), 16u);
  for (unsigned subset = 0; subset < (1u << registry.size()); ++subset)
  {
    std::vector<const LightSpaceStructure*> needed;
    std::set<const LightSpaceStructure*> expected;
    std::vector<const LightSpaceStructure*> pending;
    for (std::size_t k = 0; k < registry.size(); ++k)
    {
      if (subset & (1u << k))
      {
        needed.push_back(registry[k]);
        pending.push_back(registry[k]);
      }
    }
    while (!pending.empty())
    {
      const LightSpaceStructure* structure = pending.back();
      pending.pop_back();
      if (expected.insert(structure).second)
      {
        pending.insert(pending.end(), structure->builtFrom.begin(), structure->builtFrom.end());
      }
    }
    const std::vector<const LightSpaceStructure*> closure = withBuildDependencies(needed);
    EXPECT_EQ(std::set<const LightSpaceStructure*>(closure.begin(), closure.end()), expected) << "subset " << subset;
    EXPECT_EQ(closure.size(), expected.size()) << "subset " << subset << ": a structure listed twice";
    EXPECT_TRUE(std::is_sorted(closure.begin(), closure.end(),
      [](const LightSpaceStructure* a, const LightSpaceStructure* b) { return registryIndex(a) < registryIndex(b); }))
      << "subset " << subset << ": not in build order";
  }
}

TEST(LightSpaceStructureRegistry, AStructureMissingFromTheRegistryIsAnError)
{
  LightSpaceStructure unregistered;
  unregistered.name = "unregistered";
  unregistered.builtFrom = { &shadowMapStructure() };
  // An invariant (a structure someone forgot to register), so it aborts naming the registry.
  EXPECT_DEATH(withBuildDependencies({ &unregistered }), "missing from lightSpaceStructureRegistry");
}

// A technique declares each parameter of every structure it gets built (its own and what they are built from):
// the structure's build reads the technique's value, so it must exist with the same meaning and stay inside
// the range the build accepts.
TEST(LightSpaceStructureRegistry, TechniquesDeclareTheirStructuresParametersCompatibly)
{
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    for (const LightSpaceStructure* structure : technique.lightStructures)
    {
      ASSERT_NE(structure, nullptr) << technique.name;
      EXPECT_LT(registryIndex(structure), lightSpaceStructureRegistry().size())
        << technique.name << " lists " << structure->name << ", which is not in the registry";
    }
    for (const LightSpaceStructure* structure : withBuildDependencies(technique.lightStructures))
    {
      for (const ParameterSpec& wanted : structure->parameters)
      {
        const std::string label = technique.name + " / " + structure->name + "." + wanted.name;
        const ParameterSpec* declared = findParameterSpec(technique.parameters, wanted.name);
        ASSERT_NE(declared, nullptr) << label << ": the technique does not declare it";
        EXPECT_EQ(declared->choices, wanted.choices) << label;
        EXPECT_EQ(declared->integer, wanted.integer) << label;
        EXPECT_GE(declared->minValue, wanted.minValue) << label;
        EXPECT_LE(declared->maxValue, wanted.maxValue) << label;
        EXPECT_EQ(declared->automatic, wanted.automatic) << label;
        if (!isAutomaticValue(*declared, declared->defaultValue))
        {
          EXPECT_GE(declared->defaultValue, wanted.minValue) << label;
          EXPECT_LE(declared->defaultValue, wanted.maxValue) << label;
        }
      }
    }
  }
}

TEST(LightSpaceStructureRegistry, EveryTechniqueWithAStructureGetsTheShadowMap)
{
  int withStructures = 0;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    if (technique.lightStructures.empty())
    {
      continue; // object-space or its own maps (shadow-volume, vtk, reference-sm)
    }
    const std::vector<const LightSpaceStructure*> built = withBuildDependencies(technique.lightStructures);
    if (built == std::vector<const LightSpaceStructure*>{ &lightSampleSetStructure() })
    {
      continue; // object-space with light samples only (dcs)
    }
    ++withStructures;
    EXPECT_EQ(built.front(), &shadowMapStructure()) << technique.name << " builds no shadow map first";
  }
  EXPECT_GT(withStructures, 0);
}

// stats.json times each stage by name: a technique's stages must not share a name, or two timings would read as
// one stage.
TEST(LightSpaceStructureRegistry, EachTechniquesBuildStagesHaveDistinctNames)
{
  const std::set<std::string> pipelineStages = { "gbuffer", "technique", "sublight_accumulate", "shading" };
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    std::set<std::string> stages = pipelineStages;
    for (const LightSpaceStructure* structure : withBuildDependencies(technique.lightStructures))
    {
      for (const std::string& stage : buildStageNames(*structure))
      {
        EXPECT_TRUE(stages.insert(stage).second)
          << technique.name << ": stage " << stage << " of " << structure->name << " is timed twice";
      }
    }
  }
}

// Each structure's settings read only what the structure declares (a technique's parameters beyond those are
// optional), so they work on the structure's own table at its defaults.
TEST(LightSpaceStructureSettings, ReadTheStructuresOwnParametersAtTheirDefaults)
{
  const ParameterValues shadowMap("shadow_map", shadowMapStructure().parameters);
  const ShadowMapSettings mapSettings = ShadowMapSettings::from(shadowMap);
  // shadow_map_size = auto by default: the focus stage chooses (AutomaticMapSize.h).
  EXPECT_TRUE(mapSettings.automaticResolution);
  EXPECT_EQ(mapSettings.resolution, 0);
  EXPECT_EQ(mapSettings.marginTexels, 1.0);
  EXPECT_FALSE(mapSettings.secondDepth);

  const ParameterValues moments("moment_map", momentMapStructure().parameters);
  const MomentMapSettings momentSettings = MomentMapSettings::from(moments);
  EXPECT_FALSE(momentSettings.mipmap);
  EXPECT_EQ(momentSettings.blurTexels, moments.getInt("prefilter_texels"));
  EXPECT_EQ(momentSettings.esmExponent, 0.0);

  const ParameterValues table("summed_area_table", summedAreaTableStructure().parameters);
  EXPECT_EQ(summedAreaTableSettings(table).integer, table.choice("sat_precision") == "int32");

  const ParameterValues hsm("hierarchical_shadow_map", hierarchicalShadowMapStructure().parameters);
  EXPECT_EQ(hsm.choice("hsm"), "mipmap");
  EXPECT_EQ(hierarchicalShadowMapSettings(hsm).layout, HsmLayout::MipMap);
}

TEST(LightSpaceStructureSettings, ShadowMapSettingsFollowTheParameters)
{
  ParameterValues pcf = findTechnique("pcf").defaultParameters();
  pcf.set("shadow_map_size=300");
  for (const int kernel : { 1, 2, 3, 8, 9 })
  {
    pcf.set("kernel_texels", kernel);
    const ShadowMapSettings settings = shadowMapSettings(findTechnique("pcf"), pcf);
    EXPECT_EQ(settings.resolution, 300);
    // A kernel of k texels reaches k / 2 texels past the receiver, plus one for the bilinear footprint.
    EXPECT_EQ(settings.marginTexels, std::ceil(kernel / 2.0) + 1.0) << "kernel_texels=" << kernel;
  }
  EXPECT_FALSE(shadowMapSettings(findTechnique("pcf"), pcf).secondDepth);
  pcf.set("caster_faces=back");
  EXPECT_TRUE(shadowMapSettings(findTechnique("pcf"), pcf).secondDepth);

  // hard has no filter kernel: one texel of margin.
  ParameterValues hard = findTechnique("hard").defaultParameters();
  ASSERT_FALSE(hard.has("kernel_texels"));
  EXPECT_EQ(shadowMapSettings(findTechnique("hard"), hard).marginTexels, 1.0);

  // The moment techniques' prefilter box reaches as far as a pcf kernel of its width: the same margin, so vsm and
  // pcf over one box focus the same map.
  for (const std::string technique : { "vsm", "esm" })
  {
    ParameterValues moments = findTechnique(technique).defaultParameters();
    for (const int width : { 1, 5, 21 })
    {
      moments.set("prefilter_texels", width);
      pcf.set("kernel_texels", width);
      EXPECT_EQ(shadowMapSettings(findTechnique(technique), moments).marginTexels, shadowMapSettings(findTechnique("pcf"), pcf).marginTexels)
        << technique << " prefilter_texels=" << width;
    }
  }

  // A margin that leaves no texel for the receivers is an input error naming the filter.
  pcf.set("shadow_map_size=16");
  pcf.set("kernel_texels", 13);
  EXPECT_THROW(shadowMapSettings(findTechnique("pcf"), pcf), InputError) << "2 x 8 texels of margin on a 16-texel map";
  try
  {
    shadowMapSettings(findTechnique("pcf"), pcf);
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("--set kernel_texels=13: the filter reaches 8 texels past the receivers", 0), 0u)
      << error.what();
  }
  pcf.set("kernel_texels", 11);
  EXPECT_EQ(shadowMapSettings(findTechnique("pcf"), pcf).marginTexels, 7.0);
}

TEST(LightSpaceStructureSettings, MomentMapSettingsFollowThePrefilter)
{
  ParameterValues vsm = findTechnique("vsm").defaultParameters();
  vsm.set("prefilter=blur");
  vsm.set("prefilter_texels=7");
  MomentMapSettings settings = momentMapSettings(findTechnique("vsm"), vsm);
  EXPECT_FALSE(settings.mipmap);
  EXPECT_EQ(settings.blurTexels, 7);
  EXPECT_EQ(settings.esmExponent, 0.0) << "vsm has no esm_exponent: the third moment is unused";
  // The mip chain does the filtering: no blur, whatever prefilter_texels says.
  vsm.set("prefilter=mipmap");
  settings = momentMapSettings(findTechnique("vsm"), vsm);
  EXPECT_TRUE(settings.mipmap);
  EXPECT_EQ(settings.blurTexels, 1);

  ParameterValues esm = findTechnique("esm").defaultParameters();
  esm.set("esm_exponent=12.5");
  esm.set("prefilter_texels=3");
  settings = momentMapSettings(findTechnique("esm"), esm);
  EXPECT_EQ(settings.esmExponent, 12.5);
  EXPECT_EQ(settings.blurTexels, esm.choice("prefilter") == "mipmap" ? 1 : 3);
}

TEST(LightSpaceStructureSettings, SummedAreaTablePrecisionFollowsTheParameter)
{
  ParameterValues savsm = findTechnique("savsm").defaultParameters();
  savsm.set("sat_precision=float_centred");
  EXPECT_FALSE(summedAreaTableSettings(savsm).integer);
  savsm.set("sat_precision=int32");
  EXPECT_TRUE(summedAreaTableSettings(savsm).integer);
  ParameterValues vssm = findTechnique("vssm").defaultParameters();
  vssm.set("sat_precision=float_centred");
  EXPECT_FALSE(summedAreaTableSettings(vssm).integer);
}

TEST(LightSpaceStructureSettings, HierarchicalShadowMapLayoutFollowsTheParameter)
{
  for (const std::string technique : { "vssm", "gbp06", "gbp07" })
  {
    ParameterValues values = findTechnique(technique).defaultParameters();
    values.set("hsm=nbuffers");
    EXPECT_EQ(hierarchicalShadowMapSettings(values).layout, HsmLayout::NBuffers) << technique;
    values.set("hsm=mipmap");
    EXPECT_EQ(hierarchicalShadowMapSettings(values).layout, HsmLayout::MipMap) << technique;
    values.set("hsm=ysm");
    EXPECT_EQ(hierarchicalShadowMapSettings(values).layout, HsmLayout::Ysm) << technique;
  }
}

} // namespace
} // namespace sl
