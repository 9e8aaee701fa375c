#include "techniques/referencesm/ReferenceSmTechnique.h"

#include "techniques/ApproximationRules.h"

#include "lightspace/LightSamples.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/AlphaTexture.h"
#include "scene/RayTriangle.h"
#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/referencesm/vtkSLReferenceShadowMapPass.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace sl
{

ReferenceSmSettings ReferenceSmSettings::from(const ParameterValues& values)
{
  ReferenceSmSettings settings;
  settings.shadowMap = ShadowMapSettings::from(values);
  settings.bias = biasSettings(values);
  settings.samples = values.getInt("samples");
  settings.seed = static_cast<std::uint64_t>(values.getInt("seed"));
  return settings;
}

TechniqueDescriptor referenceSmTechnique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("reference-sm",
    "Accumulated hard shadow maps from K light samples (GPU reference)",
    "the papers' reference, e.g. VSSM (Yang et al. 2010) §7; survey §5 bias per map", 1024);
  // K maps per frame
  descriptor.addParameters({
    { "samples", 256, 1, 4096, "light samples", "K: shadow maps rendered from points spread over the area light (papers: 1024)", {}, true },
    { "seed", 1, 0, 2147483647, "", "rotation of the Hammersley light samples (Cranley-Patterson)", {}, true },
  });
  descriptor.lightStructures = {}; // it renders its own K maps
  descriptor.buffers = {
    { "visibility_stderr", "", "standard error of the visibility estimate over the K samples (Bernoulli bound)" },
    { "sample_count", "light samples", "light samples averaged in the pixel" },
    { "edge_samples", "light samples", "light samples whose hard test a texel next to the receiver's, in that "
      "sample's map, decides otherwise: a caster's edge within a texel, which each map places only to within one" },
  };
  descriptor.createPass = newTechniquePass<vtkSLReferenceShadowMapPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probeReferenceSm(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // K hard shadow maps from points on the light, averaged: the area integral up to the K samples' noise, which
  // visibility_stderr publishes (the differential test adds it to the tolerance).
  descriptor.accuracy.reference = ReferenceModel::AreaLight;
  descriptor.accuracy.tolerance = 0.02;
  descriptor.accuracy.lightSampleCount = [](const ParameterValues& values) { return ReferenceSmSettings::from(values).samples; };
  // Each of the K maps samples an alpha-textured caster at its texel centres, as every shadow map does: flagged where
  // the segment to one of the K samples crosses such a caster.
  // A caster just below the light makes each sample's map span a huge angle (its focus fits the receivers on that
  // caster too): the texels, and the bias with them, can then exceed the receiver's own distance (differential seed 1).
  descriptor.accuracy.approximations = { { "perforated caster in the map",
    "the segment from the point to one of the K light samples crosses a caster with an alpha texture: each sample's "
    "map samples its holes at texel centres" },
    { "coarse shadow map", "in one of the K maps the receiver's texel is so wide that its margin (one texel plus two "
      "per unit slope, about the depth bias) exceeds 5% of the distance to the sample" },
    { "edge within a texel", "more than the tolerance (2%) of the K samples are edge_samples: a texel next to the "
      "receiver's decides their test otherwise, so each may count either way (a map places an edge to within a "
      "texel)" } };
  descriptor.accuracy.markApproximations = [tolerance = descriptor.accuracy.tolerance](
                                             const ApproximationContext& context, ImageF& codes) {
    const ParameterValues& values = context.frame->parameters;
    // Differential seed 4: 28 of 256 samples blocked by a quad whose edge their segments pass within a texel of.
    const ImageF& edgeSamples = context.frame->find("edge_samples")->image;
    const ImageF& sampleCount = context.frame->find("sample_count")->image;
    const auto markEdges = [&] {
      for (int y = 0; y < codes.height; ++y)
      {
        for (int x = 0; x < codes.width; ++x)
        {
          if (codes.at(x, y) == 0.0f && edgeSamples.at(x, y) > tolerance * sampleCount.at(x, y))
          {
            codes.at(x, y) = 3.0f;
          }
        }
      }
    };
    const Light& light = context.scene->lights.at(static_cast<std::size_t>(context.lightIndex));
    if (light.type == LightType::Directional)
    {
      markCentreRayThroughPerforatedCaster(context, codes, 1.0f);
      markEdges();
      return;
    }
    const ReferenceSmSettings settings = ReferenceSmSettings::from(values);
    markSampleRaysThroughPerforatedCaster(context, lightSamplePoints(light, settings.samples, settings.seed), codes, 1.0f);
    // The K views as the replay fits them (the pass's own are internal); the margin is ShadowMapFootprint's.
    const ReferenceSmReplay replay(*context.frame, *context.scene, context.lightIndex);
    const ImageF& position = context.frame->find("position")->image;
    const ImageF& normal = context.frame->find("normal")->image;
    const ImageF& coverage = context.frame->find("coverage")->image;
    for (int y = 0; y < codes.height; ++y)
    {
      for (int x = 0; x < codes.width; ++x)
      {
        if (codes.at(x, y) != 0.0f || coverage.at(x, y) <= 0.5f)
        {
          continue;
        }
        const glm::dvec3 pWs(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
        const glm::dvec3 nWs(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
        for (int k = 0; k < replay.sampleCount(); ++k)
        {
          const LightView& view = replay.sampleView(k);
          const double d = projectToShadowMap(view, pWs).depthLin;
          const double tanTheta = tanAngleToLight(nWs, glm::normalize(view.eyeWs - pWs));
          if (d > 0.0 && view.texelWorldSize(d) * (1.0 + 2.0 * std::min(tanTheta, 10.0)) > 0.05 * d)
          {
            codes.at(x, y) = 2.0f;
            break;
          }
        }
      }
    }
    markEdges();
  };
  return descriptor;
}

ReferenceSmReplay::ReferenceSmReplay(const FrameResult& frame, const Scene& scene, int lightIndex)
  : light_(scene.lights.at(static_cast<std::size_t>(lightIndex)))
  , bias_(ReferenceSmSettings::from(frame.parameters).bias)
{
  const ReferenceSmSettings settings = ReferenceSmSettings::from(frame.parameters);
  inputs_.camera = frame.camera;
  inputs_.position = frame.find("position")->image;
  inputs_.normal = frame.find("normal")->image;
  inputs_.coverage = frame.find("coverage")->image;
  inputs_.receives = frame.find("receives_shadows")->image;

  // The G-buffer as the focus fit reads it (ImageReceivers: xyz + coverage, xyz + receives).
  const int width = inputs_.position.width;
  const int height = inputs_.position.height;
  ImageF positionRgba(width, height, 4);
  ImageF normalRgba(width, height, 4);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        positionRgba.at(x, y, c) = inputs_.position.at(x, y, c);
        normalRgba.at(x, y, c) = inputs_.normal.at(x, y, c);
      }
      positionRgba.at(x, y, 3) = inputs_.coverage.at(x, y);
      normalRgba.at(x, y, 3) = inputs_.receives.at(x, y);
    }
  }
  ImageReceivers receivers(positionRgba, normalRgba);
  // As vtkSLReferenceShadowMapPass::Execute: the samples, a point light of the area light's orientation at each,
  // its map focused with a one-texel margin.
  const std::vector<glm::dvec3> samples = lightSamplePoints(light_, settings.samples, settings.seed);
  const bool directional = light_.type == LightType::Directional;
  const std::size_t sampleCount = directional ? 1 : samples.size();
  FocusSettings focus;
  // shadow_map_size = auto: the size the pass chose (from the centre's map, AutomaticMapSize.h).
  SL_CHECK(!settings.shadowMap.automaticResolution || frame.automaticMapSize);
  focus.resolution = settings.shadowMap.automaticResolution ? frame.automaticMapSize->size : settings.shadowMap.resolution;
  focus.marginTexels = settings.shadowMap.marginTexels;
  lights_.reserve(sampleCount);
  for (std::size_t k = 0; k < sampleCount; ++k)
  {
    Light sampleLight = light_;
    if (!directional)
    {
      sampleLight.center = samples[k];
    }
    lights_.push_back(sampleLight);
    views_.push_back(fitLightView(lights_.back(), scene, receivers, focus));
    worldFromClip_.push_back(glm::inverse(views_.back().clipFromWorld));
  }

  backFaces_ = settings.shadowMap.secondDepth;
  for (const SceneObject& object : scene.objects)
  {
    if (!object.castShadows)
    {
      continue;
    }
    const TriangleMesh& mesh = object.mesh;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
    {
      const std::uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
      Triangle triangle;
      triangle.a = glm::dvec3(mesh.positions[i0]);
      triangle.edge1 = glm::dvec3(mesh.positions[i1]) - triangle.a;
      triangle.edge2 = glm::dvec3(mesh.positions[i2]) - triangle.a;
      triangle.normal = glm::cross(triangle.edge1, triangle.edge2);
      if (!mesh.uvs.empty())
      {
        triangle.uvA = glm::dvec2(mesh.uvs[i0]);
        triangle.uvB = glm::dvec2(mesh.uvs[i1]);
        triangle.uvC = glm::dvec2(mesh.uvs[i2]);
      }
      triangle.alpha = object.hasAlphaTexture ? &object.alphaTexture.alpha : nullptr;
      casters_.push_back(triangle);
    }
  }
}

double ReferenceSmReplay::storedDepth(std::size_t k, const glm::dvec2& texelPosition) const
{
  const LightView& view = views_[k];
  // The ray through the position from the near to the far plane (clip z = -1 .. 1): what the rasteriser covers
  // there, clipped to the view's depth range as the hardware clips it.
  const glm::dvec2 ndc = texelPosition / static_cast<double>(view.resolution) * 2.0 - 1.0;
  glm::dvec4 nearPoint = worldFromClip_[k] * glm::dvec4(ndc, -1.0, 1.0);
  glm::dvec4 farPoint = worldFromClip_[k] * glm::dvec4(ndc, 1.0, 1.0);
  const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
  const glm::dvec3 direction = glm::dvec3(farPoint) / farPoint.w - origin;
  double nearest = 2.0 * view.farDepth; // the clear value: no caster covers the texel
  for (const Triangle& triangle : casters_)
  {
    const double facing = glm::dot(triangle.normal, direction);
    // caster_faces = back (second-depth): only faces turned away from the light (gl_FrontFacing false); an
    // edge-on triangle covers nothing.
    if (facing == 0.0 || (backFaces_ && facing < 0.0))
    {
      continue;
    }
    const std::optional<RayTriangleHit> hit =
      intersectRayTriangle(origin, direction, triangle.a, triangle.edge1, triangle.edge2);
    if (!hit || hit->t < 0.0 || hit->t > 1.0)
    {
      continue;
    }
    if (triangle.alpha != nullptr)
    {
      const glm::dvec2 uv = (1.0 - hit->u - hit->v) * triangle.uvA + hit->u * triangle.uvB + hit->v * triangle.uvC;
      if (alphaHoleAt(*triangle.alpha, uv))
      {
        continue; // a hole: the light-depth pass discards it
      }
    }
    const glm::dvec3 hitPoint = origin + hit->t * direction;
    nearest = std::min(nearest, -(view.viewFromWorld * glm::dvec4(hitPoint, 1.0)).z);
  }
  return nearest;
}

ReferenceSmReplay::Pixel ReferenceSmReplay::replay(glm::ivec2 pixel, ProbeRecorder* recorder)
{
  Pixel result;
  const int sampleCount = static_cast<int>(lights_.size());
  // Float accumulation of K weights 1/K into the R32F target: at most one rounding of 2^-24 per addition.
  const double accumulation = sampleCount * std::ldexp(1.0, -24);
  result.tolerance = accumulation;
  if (inputs_.coverage.at(pixel.x, pixel.y) <= 0.5f)
  {
    return result;
  }
  const glm::dvec3 pWs(inputs_.position.at(pixel.x, pixel.y, 0), inputs_.position.at(pixel.x, pixel.y, 1),
    inputs_.position.at(pixel.x, pixel.y, 2));
  const glm::dvec3 nWs(inputs_.normal.at(pixel.x, pixel.y, 0), inputs_.normal.at(pixel.x, pixel.y, 1),
    inputs_.normal.at(pixel.x, pixel.y, 2));
  if (recorder)
  {
    recorder->beginGroup("receiver");
    recorder->quantity("position", pWs, "world units", "G-buffer (pWs)");
    recorder->quantity("normal", nWs, "", "G-buffer (nWs)");
    recorder->beginGroup("light samples");
    recorder->quantity("samples", sampleCount, "light samples",
      "VSSM (Yang et al. 2010) §7: K shadow maps from points spread over the light (Hammersley, rotated by seed)");
    recorder->quantity("shadow_map_size", views_.front().resolution, "texels", "ShadowLab (shadow_map_size): each sample's map");
  }
  if (inputs_.receives.at(pixel.x, pixel.y) <= 0.5f)
  {
    result.visibility = 1.0;
    if (recorder)
    {
      recorder->category("receives_shadows", "no: lit, no shadow test", "ShadowLab (receive_shadows)");
    }
    return result;
  }
  result.evaluated = true;
  int blocked = 0;
  for (std::size_t k = 0; k < lights_.size(); ++k)
  {
    inputs_.light = &lights_[k];
    inputs_.lightView = views_[k];
    const ShadowLookup lookup = prepareShadowLookup(inputs_, bias_, pixel.x, pixel.y);
    bool uncertain = lookup.sample.reachMargin < probeReachAmbiguity;
    bool lit = false;
    if (!lookup.sample.evaluated)
    {
      ++result.unreachable; // below the receiver's horizon for this sample, or behind the light's plane
    }
    else
    {
      const int size = views_[k].resolution;
      const glm::dvec2 uv = lookup.sm.uvTexels;
      const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(uv)), glm::ivec2(0), glm::ivec2(size - 1));
      const glm::dvec2 centre = glm::dvec2(texel) + 0.5;
      const double compared = lookup.comparisonDepth;
      const double stored = storedDepth(k, centre);
      lit = compared <= stored; // ReferenceSmAccumulate.glsl: shadowTest, as `hard`
      const auto decidesOtherwise = [&](const glm::dvec2& position) { return (compared <= storedDepth(k, position)) != lit; };
      uncertain = uncertain || std::abs(compared - stored) < probeDepthAmbiguity * std::max(1e-30, std::abs(stored));
      for (const glm::dvec2& shift : { glm::dvec2(kTexelMargin, 0.0), glm::dvec2(-kTexelMargin, 0.0),
             glm::dvec2(0.0, kTexelMargin), glm::dvec2(0.0, -kTexelMargin) })
      {
        uncertain = uncertain || decidesOtherwise(centre + shift);
      }
      for (const TexelEdge& edge : texelWithEdges(uv).edges)
      {
        const glm::ivec2 neighbour = glm::clamp(edge.neighbour, glm::ivec2(0), glm::ivec2(size - 1));
        uncertain = uncertain || (edge.distance < kTexelMargin && neighbour != texel && decidesOtherwise(glm::dvec2(neighbour) + 0.5));
      }
      // ReferenceSmAccumulate.glsl's edgeWithinATexel: the four texels next to the receiver's (clamped), each
      // decided at its centre; a neighbour whose centre lies within kTexelMargin of a coverage change, or whose
      // stored depth is within rounding of the comparison, may be decided either way on the GPU.
      bool edge = false;
      bool edgeUncertain = uncertain;
      for (const glm::ivec2& step : { glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1) })
      {
        const glm::dvec2 neighbourCentre = glm::dvec2(glm::clamp(texel + step, glm::ivec2(0), glm::ivec2(size - 1))) + 0.5;
        const double neighbourStored = storedDepth(k, neighbourCentre);
        const bool neighbourLit = compared <= neighbourStored;
        edge = edge || neighbourLit != lit;
        edgeUncertain = edgeUncertain ||
          std::abs(compared - neighbourStored) < probeDepthAmbiguity * std::max(1e-30, std::abs(neighbourStored));
        for (const glm::dvec2& shift : { glm::dvec2(kTexelMargin, 0.0), glm::dvec2(-kTexelMargin, 0.0),
               glm::dvec2(0.0, kTexelMargin), glm::dvec2(0.0, -kTexelMargin) })
        {
          edgeUncertain = edgeUncertain || (compared <= storedDepth(k, neighbourCentre + shift)) != neighbourLit;
        }
      }
      result.edge += edge ? 1 : 0;
      result.edgeUncertain += edgeUncertain ? 1 : 0;
    }
    result.lit += lit ? 1 : 0;
    blocked += !lit && lookup.sample.evaluated ? 1 : 0;
    result.uncertain += uncertain ? 1 : 0;
    if (recorder)
    {
      // Light coordinates: the sample's offset from the light's centre in the light view's x and y.
      const glm::dvec3 offset = glm::dmat3(views_[k].viewFromWorld) * (lights_[k].center - light_.center);
      recorder->lightSample({ glm::dvec2(offset.x, offset.y), !lit, -1 });
    }
  }
  result.visibility = static_cast<double>(result.lit) / sampleCount;
  result.tolerance = accumulation + static_cast<double>(result.uncertain) / sampleCount;
  if (recorder)
  {
    recorder->quantity("lit_samples", result.lit, "light samples",
      "Williams 1978 per sample: d - bias <= the depth its map stores at the receiver's texel");
    recorder->quantity("blocked_samples", blocked, "light samples", "Williams 1978 per sample: a caster nearer than d - bias");
    recorder->quantity("unreachable_samples", result.unreachable, "light samples",
      "ShadowLab (lightCanReach): the sample lies below the receiver's tangent plane (or the receiver behind the light)");
    recorder->quantity("edge_samples", result.edge, "light samples",
      "ShadowLab: samples whose test a texel next to the receiver's decides otherwise (an edge within a texel)");
    recorder->quantity("uncertain_samples", result.uncertain, "light samples",
      "ShadowLab: samples float rounding, rasterisation or the fitted window may decide either way (1/128 texel, 2e-6)");
    recorder->beginGroup("result");
    recorder->quantity("sample_count", sampleCount, "light samples", "ShadowLab: light samples averaged in the pixel");
    recorder->quantity("visibility", result.visibility, "", "VSSM (Yang et al. 2010) §7: the average of the K hard shadow tests");
    recorder->quantity("visibility_stderr",
      sampleCount > 1 ? std::sqrt(result.visibility * (1.0 - result.visibility) / (sampleCount - 1)) : 0.0, "",
      "ShadowLab: Bernoulli bound sqrt(v (1 - v) / (K - 1))");
  }
  return result;
}

ProbeOutcome probeReferenceSm(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  ReferenceSmReplay replay(frame, scene, lightIndex);
  const ReferenceSmReplay::Pixel result = replay.replay(pixel, &recorder);
  ProbeOutcome outcome;
  outcome.evaluated = result.evaluated;
  outcome.visibility = result.visibility;
  // Per pixel: the GPU's K tests are replayed texel by texel, so it may differ by the float accumulation of the
  // K weights (K 2^-24) and by 1/K per sample the replay marks uncertain, no more. ReferenceSmTest holds that on
  // every pixel of three 64^2 frames; measured there (llvmpipe): |GPU - replay| = 0 on every pixel without an
  // uncertain sample (stacked-occluders K = 16, fence K = 8 with alpha-tested casters, contact with second-depth
  // maps), 0.0625 = 1/K at most where one is (9, 75 and 10 of the 4096 pixels have one).
  outcome.tolerance = result.tolerance;
  outcome.twin = "ReferenceSmReplay (referencesm/ReferenceSmTechnique.h): the K samples' hard tests, each map's "
                 "texel replayed by a ray through its centre (nearest caster, Moller-Trumbore in double), views "
                 "fitted on the CPU";
  return outcome;
}

} // namespace sl
