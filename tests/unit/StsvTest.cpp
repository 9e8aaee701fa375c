// Soft textured shadow volumes' CPU core (src/objectspace/StsvGeometry.h; Forest et al. 2009 §2.2-2.4, Eq. 1-5), without
// GL. Eq. 1's homogeneous barycentrics against Moller-Trumbore (scene/RayTriangle.h) over 10^5 random cases, which
// decides the reconstruction of W (1/e, not the text's 1); the paper's occlusion test with and without ShadowLab's
// opposite-side check; the volume's conservativeness over 10^6 random points (a sample the triangle hides implies the
// point is inside the STSV of that sample's side) and its tightness (a point light gives exactly the hard shadow
// volume; each outer plane touches the shadow); Fig. 6's strip; an opaque quad against the closed form of a square
// light over a parallel rectangle; and the hard cases (points on the perforated triangle, a
// plate just above the fence, a light straddling the triangle's plane).
#include "lightspace/LightSampleSet.h"
#include "lightspace/LightSamples.h"
#include "scene/AlphaTexture.h"
#include "scene/RayTriangle.h"
#include "scene/Scene.h"
#include "objectspace/StsvGeometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace sl
{
namespace
{

using Random = std::mt19937_64;

using test::uniform;

glm::dvec3 uniformIn(Random& random, const glm::dvec3& low, const glm::dvec3& high)
{
  return glm::dvec3(uniform(random, low.x, high.x), uniform(random, low.y, high.y), uniform(random, low.z, high.z));
}

glm::dvec3 pointOn(const StsvTriangle& triangle, double u, double v)
{
  const auto& t = triangle.vertices;
  return t[0] + u * (t[1] - t[0]) + v * (t[2] - t[0]);
}

// A random triangle around `centre` that is not a sliver (twice its area at least 0.1 of its longest edge squared),
// with random texture coordinates.
StsvTriangle randomTriangle(Random& random, const glm::dvec3& centre, double spread)
{
  for (;;)
  {
    const glm::dvec3 v0 = centre + spread * uniformIn(random, glm::dvec3(-1.0), glm::dvec3(1.0));
    const glm::dvec3 v1 = centre + spread * uniformIn(random, glm::dvec3(-1.0), glm::dvec3(1.0));
    const glm::dvec3 v2 = centre + spread * uniformIn(random, glm::dvec3(-1.0), glm::dvec3(1.0));
    const double longest = std::max({ glm::length(v1 - v0), glm::length(v2 - v1), glm::length(v0 - v2) });
    if (glm::length(glm::cross(v1 - v0, v2 - v0)) < 0.1 * longest * longest)
    {
      continue;
    }
    const auto texCoord = [&] { return glm::dvec2(uniform(random, -1.0, 2.0), uniform(random, -1.0, 2.0)); };
    return makeStsvTriangle(v0, v1, v2, texCoord(), texCoord(), texCoord());
  }
}

// Where the line p + lambda (s - p) meets t's plane, by Cramer's rule on the plane's dual basis: an independent third
// computation, used only to tell which cases lie within a rounding band of a decision (ambiguous).
struct LineHit
{
  double lambda = 0.0;
  double u = 0.0;
  double v = 0.0;
  bool parallel = true;
};

LineHit lineHit(const StsvTriangle& triangle, const glm::dvec3& p, const glm::dvec3& s)
{
  LineHit hit;
  const auto& t = triangle.vertices;
  const glm::dvec3 e1 = t[1] - t[0];
  const glm::dvec3 e2 = t[2] - t[0];
  const glm::dvec3 d = s - p;
  const double denominator = glm::dot(triangle.normal, d);
  if (denominator == 0.0)
  {
    return hit;
  }
  hit.parallel = false;
  hit.lambda = glm::dot(triangle.normal, t[0] - p) / denominator;
  const glm::dvec3 x = p + hit.lambda * d - t[0];
  const double e11 = glm::dot(e1, e1), e12 = glm::dot(e1, e2), e22 = glm::dot(e2, e2);
  const double determinant = e11 * e22 - e12 * e12;
  hit.u = (e22 * glm::dot(x, e1) - e12 * glm::dot(x, e2)) / determinant;
  hit.v = (e11 * glm::dot(x, e2) - e12 * glm::dot(x, e1)) / determinant;
  return hit;
}

// Within `band` of an edge of t, of p or s along the line, or (with an alpha texture) of a texel boundary.
bool ambiguous(const StsvTriangle& triangle, const ImageF* alpha, const glm::dvec3& p, const glm::dvec3& s, double band)
{
  const LineHit hit = lineHit(triangle, p, s);
  if (hit.parallel)
  {
    return true;
  }
  if (std::abs(hit.u) < band || std::abs(hit.v) < band || std::abs(1.0 - hit.u - hit.v) < band ||
    std::abs(hit.lambda - 1.0) < band || std::abs(hit.lambda) < band)
  {
    return true;
  }
  if (alpha != nullptr && hit.u >= 0.0 && hit.v >= 0.0 && hit.u + hit.v <= 1.0)
  {
    const auto& tc = triangle.texCoords;
    const glm::dvec2 uv = (1.0 - hit.u - hit.v) * tc[0] + hit.u * tc[1] + hit.v * tc[2];
    const double x = uv.x * alpha->width;
    const double y = uv.y * alpha->height;
    if (std::abs(x - std::round(x)) < band * alpha->width || std::abs(y - std::round(y)) < band * alpha->height)
    {
      return true;
    }
  }
  return false;
}

// The ray tracer's decision for (p, s): the open segment crosses t (Moller-Trumbore) at an opaque texel.
bool rayTracedOccluded(const StsvTriangle& triangle, const ImageF& alpha, const glm::dvec3& p, const glm::dvec3& s)
{
  const auto& t = triangle.vertices;
  const std::optional<RayTriangleHit> hit = intersectRayTriangle(p, s - p, t[0], t[1] - t[0], t[2] - t[0]);
  if (!hit || !(hit->t > 0.0 && hit->t < 1.0))
  {
    return false;
  }
  const auto& tc = triangle.texCoords;
  return !alphaHoleAt(alpha, (1.0 - hit->u - hit->v) * tc[0] + hit->u * tc[1] + hit->v * tc[2]);
}

ImageF opaqueAlpha()
{
  return ImageF(4, 4, 1, 1.0f);
}

Light squareLight(const glm::dvec3& centre, double size, const glm::dvec3& normal)
{
  Light light;
  light.type = LightType::Area;
  light.shape = LightShape::Square;
  light.center = centre;
  light.normal = glm::normalize(normal);
  light.up = glm::normalize(glm::dvec3(0.0, 0.0, 1.0) - glm::dot(glm::dvec3(0.0, 0.0, 1.0), light.normal) * light.normal);
  light.size = size;
  return light;
}

// The light samples of the conservativeness tests: N stratified points of the shared set (pixel `index`), plus the
// light's 4 corners and 4 edge midpoints (unit coordinates 0, 1/2, 1), the extreme points that reach the shadow's
// outer boundary.
std::vector<glm::dvec3> samplesWithExtremes(const LightSampleSet& set, const Light& light, int index)
{
  std::vector<glm::dvec3> samples;
  for (int i = 0; i < set.count(); ++i)
  {
    samples.push_back(set.point(light, index % 4096, index / 4096, i));
  }
  for (const double u : { 0.0, 0.5, 1.0 })
  {
    for (const double v : { 0.0, 0.5, 1.0 })
    {
      if (u != 0.5 || v != 0.5)
      {
        samples.push_back(pointOnAreaLight(light, glm::dvec2(u, v)));
      }
    }
  }
  return samples;
}

double secondsSince(const std::chrono::steady_clock::time_point& start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- Eq. 1-5 -----------------------------------------------------------------------------------------------------

// The four readings of Eq. 1/3 the test tells apart: the derived W (last entry 1/e, signed e, applied to s - p), the
// text's last entry 1, an unsigned e ("orthogonal distance", §2.4), and J applied to the world sample s itself.
enum class Reading
{
  Derived,
  TextLastEntryOne,
  UnsignedDistance,
  WorldSample,
};

glm::dvec3 homogeneousBarycentric(
  Reading reading, const StsvTriangle& triangle, const glm::dvec3& p, const glm::dvec3& s)
{
  const glm::dvec3 q = triangle.triangleFromWorld * (triangle.vertices[0] - p);
  const double e = reading == Reading::UnsignedDistance ? std::abs(q.z) : q.z;
  const double last = reading == Reading::TextLastEntryOne ? 1.0 : 1.0 / e;
  const glm::dmat3 w(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(-q.x / e, -q.y / e, last));
  const glm::dmat3 j = w * triangle.triangleFromWorld;
  return reading == Reading::WorldSample ? j * s : j * (s - p);
}

// Over 10^5 random (triangle, p, s): Eq. 1's s*_h = J (s - p) gives Moller-Trumbore's barycentrics (u = x/z, v = y/z)
// and line parameter (lambda = 1/z), Eq. 5 its texture coordinate, and the occlusion decision equals the segment's
// (with the fence's alpha, the ray tracer's alpha filter). Cases: p at a signed height 1e-6..2 (log-uniform) on either
// side, the line's plane point inside t (70 %) or around it, s with the plane between p and s, beyond s (s on p's
// side) or behind p. Both computations round; where the line grazes the plane (sin of its angle to it below 1e-2) the
// problem itself amplifies rounding by ~1/sin, so there the bound is 1e-12 scaled by 1e-2/sin (measured: 6.5e-10 at
// sin ~ 4e-7). lambda is compared as the hit's position along the line (|delta lambda| |s - p|, world units): lambda
// itself is e / d_h, and e of a point 1e-6 off the plane carries a relative rounding of ~1e-10 in both methods. The
// same cases measure the other readings of W: each must fail.
TEST(StsvEq1, HomogeneousBarycentricsEqualRayTriangleAndDecideW)
{
  const auto start = std::chrono::steady_clock::now();
  Random random(20090611);
  const ImageF fence = makeFenceAlpha();
  constexpr int kCases = 100000;
  constexpr double kGrazingSin = 1e-2; // 0.57 degrees
  const std::vector<Reading> readings{ Reading::Derived, Reading::TextLastEntryOne, Reading::UnsignedDistance,
    Reading::WorldSample };
  std::map<Reading, double> maxError; // over well-conditioned hits (sin >= kGrazingSin)
  std::map<Reading, int> wrongDecisions;
  for (const Reading reading : readings)
  {
    maxError[reading] = 0.0;
    wrongDecisions[reading] = 0;
  }
  double maxScaledError = 0.0;  // production path, every hit, error x min(1, sin / kGrazingSin)
  double maxRawError = 0.0;     // production path, every hit, unscaled (for the report)
  double maxLambdaError = 0.0;  // |delta lambda| |s - p|, world units, scaled likewise
  double maxTexCoordError = 0.0; // scaled likewise
  int hits = 0;
  int grazingHits = 0;
  int smallE = 0; // |e| < 1e-3 among well-conditioned hits
  int ambiguousCases = 0;
  int decided = 0;
  int mismatchWithCheck = 0;
  int mismatchAlpha = 0;
  int sameSideHits = 0;      // the line meets t beyond s (lambda > 1): s on p's side of the plane
  int falseWithoutCheck = 0; // the paper's test alone calls them occluded, the ray tracer does not
  int behindHits = 0;        // lambda < 0
  int negativeE = 0;
  for (int c = 0; c < kCases; ++c)
  {
    const StsvTriangle triangle = randomTriangle(random, glm::dvec3(0.0), 1.0);
    const double height = (uniform(random, 0.0, 1.0) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, uniform(random, -6.0, 0.3));
    negativeE += height < 0.0;
    // The line's point on the plane: inside t (70 %) or around it.
    double uq = 0.0;
    double vq = 0.0;
    if (uniform(random, 0.0, 1.0) < 0.7)
    {
      uq = uniform(random, 0.0, 1.0);
      vq = uniform(random, 0.0, 1.0);
      if (uq + vq > 1.0)
      {
        uq = 1.0 - uq;
        vq = 1.0 - vq;
      }
    }
    else
    {
      uq = uniform(random, -0.25, 1.25);
      vq = uniform(random, -0.25, 1.25);
    }
    const glm::dvec3 q = pointOn(triangle, uq, vq);
    // p's foot point: anywhere near t (grazing lines when p is close to the plane), or within 20 |e| of q (a steep
    // line even at |e| = 1e-6).
    glm::dvec3 foot;
    if (uniform(random, 0.0, 1.0) < 0.5)
    {
      foot = pointOn(triangle, uniform(random, -0.5, 1.5), uniform(random, -0.5, 1.5));
    }
    else
    {
      const glm::dvec3 inPlane = glm::normalize(triangle.vertices[1] - triangle.vertices[0]);
      const glm::dvec3 other = glm::cross(triangle.normal, inPlane);
      foot = q + std::abs(height) * (uniform(random, -20.0, 20.0) * inPlane + uniform(random, -20.0, 20.0) * other);
    }
    const glm::dvec3 p = foot + height * triangle.normal;
    // lambda: the plane between p and s (45 %), beyond s (s on p's side, 35 %), behind p (20 %).
    const double bucket = uniform(random, 0.0, 1.0);
    const double lambda = bucket < 0.45 ? uniform(random, 0.02, 0.98)
      : bucket < 0.8                    ? uniform(random, 1.02, 6.0)
                                        : -uniform(random, 0.02, 4.0);
    const glm::dvec3 s = p + (q - p) / lambda;
    const double sine = std::abs(glm::dot(s - p, triangle.normal)) / glm::length(s - p);
    const double conditioning = std::min(1.0, sine / kGrazingSin);

    const auto& t = triangle.vertices;
    const std::optional<RayTriangleHit> ray = intersectRayTriangle(p, s - p, t[0], t[1] - t[0], t[2] - t[0]);
    const StsvPointTransform transform = stsvPointTransform(triangle, p, 0.0);
    ASSERT_FALSE(transform.onPlane);
    const StsvSampleEvaluation withCheck =
      evaluateStsvSample(triangle, transform, fence, p, s, StsvOcclusionTest::PaperAndOppositeSides);
    const StsvSampleEvaluation paperOnly = evaluateStsvSample(triangle, transform, fence, p, s, StsvOcclusionTest::Paper);
    const glm::dvec3 sh = withCheck.homogeneousBarycentric;
    if (ray)
    {
      ++hits;
      grazingHits += sine < kGrazingSin;
      smallE += sine >= kGrazingSin && std::abs(height) < 1e-3;
      if (sine >= kGrazingSin)
      {
        for (const Reading reading : readings)
        {
          const glm::dvec3 h = homogeneousBarycentric(reading, triangle, p, s);
          const double error = std::max(std::abs(h.x / h.z - ray->u), std::abs(h.y / h.z - ray->v));
          maxError[reading] = std::max(maxError[reading], std::isfinite(error) ? error : 1e300);
        }
      }
      // The production path (stsvPointTransform, evaluateStsvSample).
      const double error = std::max(std::abs(sh.x / sh.z - ray->u), std::abs(sh.y / sh.z - ray->v));
      maxRawError = std::max(maxRawError, error);
      maxScaledError = std::max(maxScaledError, error * conditioning);
      maxLambdaError = std::max(maxLambdaError, conditioning * std::abs(1.0 / sh.z - ray->t) * glm::length(s - p));
      if (withCheck.insideTriangle)
      {
        const auto& tc = triangle.texCoords;
        const glm::dvec2 uvRay = (1.0 - ray->u - ray->v) * tc[0] + ray->u * tc[1] + ray->v * tc[2];
        const glm::dvec3 texHomogeneous = triangle.textureFromBarycentric * sh;
        const glm::dvec2 uvEq5 = glm::dvec2(texHomogeneous) / texHomogeneous.z;
        maxTexCoordError = std::max(maxTexCoordError, conditioning * glm::length(uvEq5 - uvRay));
      }
      sameSideHits += ray->t > 1.0;
      behindHits += ray->t < 0.0;
    }
    if (ambiguous(triangle, &fence, p, s, 1e-9))
    {
      ++ambiguousCases;
      continue;
    }
    ++decided;
    const bool crosses = ray && ray->t > 0.0 && ray->t < 1.0;
    // Geometry alone: the segment crosses t <=> the paper's test and z > 1.
    mismatchWithCheck += crosses != (withCheck.insideTriangle && withCheck.oppositeSides);
    // With the fence's alpha: the ray tracer's alpha filter.
    mismatchAlpha += withCheck.occluded != rayTracedOccluded(triangle, fence, p, s);
    falseWithoutCheck += paperOnly.occluded && !rayTracedOccluded(triangle, fence, p, s);
    for (const Reading reading : readings)
    {
      const glm::dvec3 h = homogeneousBarycentric(reading, triangle, p, s);
      const bool occludedGeometrically = h.x >= 0.0 && h.y >= 0.0 && h.z >= h.x + h.y && h.z > 1.0;
      wrongDecisions[reading] += occludedGeometrically != crosses;
    }
  }
  const char* names[] = { "derived (1/e, signed e, s - p)", "text's last entry 1", "unsigned e", "J applied to world s" };
  for (std::size_t r = 0; r < readings.size(); ++r)
  {
    std::cout << "[ measured ] W reading '" << names[r] << "': max |barycentric - Moller-Trumbore| "
              << maxError[readings[r]] << " (hits with sin >= 1e-2), wrong occlusion decisions "
              << wrongDecisions[readings[r]] << " of " << decided << "\n";
  }
  std::cout << "[ measured ] derived, every hit: max error " << maxRawError << " raw, " << maxScaledError
            << " scaled by min(1, sin/1e-2); hit position along the line " << maxLambdaError << ", Eq. 5 texture coordinates "
            << maxTexCoordError << " (scaled); " << hits << " hits (" << grazingHits << " grazing, " << smallE
            << " steep with |e| < 1e-3), " << sameSideHits << " with s on p's side, " << behindHits << " behind p; "
            << negativeE << " cases with e < 0; " << ambiguousCases << " ambiguous; " << falseWithoutCheck
            << " samples the paper's test alone calls occluded falsely; " << secondsSince(start) << " s\n";
  // The decision on W: the derived reading agrees to 1e-12, every other reading is off by far more.
  EXPECT_LT(maxError[Reading::Derived], 1e-12);
  EXPECT_LT(maxScaledError, 1e-12);
  EXPECT_LT(maxLambdaError, 1e-12);
  EXPECT_LT(maxTexCoordError, 1e-11); // texture coordinates span up to 3 units here
  EXPECT_GT(maxError[Reading::TextLastEntryOne], 1e-2) << "the text's W would pass: the test could not decide";
  EXPECT_GT(maxError[Reading::UnsignedDistance], 1e-2);
  EXPECT_GT(maxError[Reading::WorldSample], 1e-2);
  EXPECT_EQ(wrongDecisions[Reading::Derived], 0);
  EXPECT_GT(wrongDecisions[Reading::TextLastEntryOne], 0);
  EXPECT_GT(wrongDecisions[Reading::UnsignedDistance], 0);
  EXPECT_GT(smallE, kCases / 20);
  EXPECT_EQ(mismatchWithCheck, 0);
  EXPECT_EQ(mismatchAlpha, 0);
  // The gap: without z > 1, samples on p's side whose line meets an opaque texel beyond them pass as occluded.
  EXPECT_GT(sameSideHits, kCases / 10);
  EXPECT_GT(falseWithoutCheck, kCases / 20);
  EXPECT_LT(ambiguousCases, kCases / 1000);
}

// ---- The volume ---------------------------------------------------------------------------------------------------

// A random (triangle, light, scene box): a light 2.5-4 high, square or disk, 0.2-2.5 wide, tilted up to ~22 degrees,
// over one of three kinds of triangle: anywhere below it (`Free`), large and close under it (`Close`: where the
// paper's front cap t' can put part of the light beyond its plane), both tilted at most ~45 degrees, or in a plane
// through a point of the light (`Straddling`: two STSVs). The box is the receivers' bounds: a 12 x 12 ground at y = 0 and the triangle.
enum class CaseKind
{
  Free,
  Close,
  Straddling,
};

struct VolumeCase
{
  StsvTriangle triangle;
  Light light;
  Bounds box;
  std::vector<Stsv> volumes;
};

VolumeCase randomVolumeCase(Random& random, CaseKind kind)
{
  VolumeCase c;
  c.light.type = LightType::Area;
  c.light.shape = uniform(random, 0.0, 1.0) < 0.5 ? LightShape::Square : LightShape::Disk;
  c.light.size = kind == CaseKind::Close ? uniform(random, 1.5, 3.0) : uniform(random, 0.2, 2.5);
  c.light.center = glm::dvec3(uniform(random, -1.0, 1.0), uniform(random, 2.5, 4.0), uniform(random, -1.0, 1.0));
  c.light.normal = glm::normalize(glm::dvec3(uniform(random, -0.4, 0.4), -1.0, uniform(random, -0.4, 0.4)));
  c.light.up = glm::normalize(glm::cross(c.light.normal, glm::dvec3(1.0, 0.0, 0.0)));
  if (kind == CaseKind::Straddling)
  {
    const glm::dvec3 through = pointOnAreaLight(c.light, glm::dvec2(uniform(random, 0.2, 0.8), uniform(random, 0.2, 0.8)));
    const glm::dvec3 planeNormal =
      glm::normalize(glm::dvec3(uniform(random, -1.0, 1.0), uniform(random, -0.3, 0.3), uniform(random, -1.0, 1.0)));
    const glm::dvec3 down =
      glm::normalize(glm::dvec3(0.0, -1.0, 0.0) - glm::dot(glm::dvec3(0.0, -1.0, 0.0), planeNormal) * planeNormal);
    const glm::dvec3 across = glm::cross(planeNormal, down);
    for (;;)
    {
      std::array<glm::dvec3, 3> v{};
      for (glm::dvec3& vertex : v)
      {
        vertex = through + uniform(random, 1.0, 3.0) * down + uniform(random, -1.2, 1.2) * across;
      }
      const double longest = std::max({ glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2]) });
      if (glm::length(glm::cross(v[1] - v[0], v[2] - v[0])) >= 0.1 * longest * longest)
      {
        c.triangle = makeStsvTriangle(v[0], v[1], v[2], glm::dvec2(0.0), glm::dvec2(1.0, 0.0), glm::dvec2(0.0, 1.0));
        break;
      }
    }
  }
  else
  {
    // Tilted at most ~45 degrees from horizontal, so that the plane mostly misses the light (a random orientation
    // cuts it in most cases, which the Straddling kind covers).
    do
    {
      c.triangle = kind == CaseKind::Close
        ? randomTriangle(random, c.light.center + glm::dvec3(0.0, -uniform(random, 0.9, 1.4), 0.0), 0.6)
        : randomTriangle(random,
            glm::dvec3(uniform(random, -0.5, 0.5), uniform(random, 0.8, 1.8), uniform(random, -0.5, 0.5)),
            uniform(random, 0.3, 1.0));
    } while (std::abs(c.triangle.normal.y) < 0.7);
  }
  c.box.extend(glm::dvec3(-6.0, 0.0, -6.0));
  c.box.extend(glm::dvec3(6.0, 0.0, 6.0));
  for (const glm::dvec3& vertex : c.triangle.vertices)
  {
    c.box.extend(vertex);
  }
  c.volumes = buildStsvs(c.triangle, c.light, c.box);
  return c;
}

const Stsv* volumeOfSide(const VolumeCase& c, int side)
{
  for (const Stsv& stsv : c.volumes)
  {
    if (stsv.lightSide == side)
    {
      return &stsv;
    }
  }
  return nullptr;
}

// The paper's front cap plane for `triangle` and centre c, recomputed here from Forest et al. 2009 §2.2 (the closest vertex
// stays, the others move towards c to its distance), positive away from c: where StsvGeometry falls back to t, this
// shows what t' would have cut off.
StsvPlane paperFrontCapPlane(const StsvTriangle& triangle, const glm::dvec3& c)
{
  const auto& v = triangle.vertices;
  const double closest = std::min({ glm::length(v[0] - c), glm::length(v[1] - c), glm::length(v[2] - c) });
  std::array<glm::dvec3, 3> moved{};
  for (std::size_t i = 0; i < 3; ++i)
  {
    moved[i] = c + (v[i] - c) * (closest / glm::length(v[i] - c));
  }
  glm::dvec3 normal = glm::normalize(glm::cross(moved[1] - moved[0], moved[2] - moved[0]));
  if (glm::dot(normal, c - moved[0]) > 0.0)
  {
    normal = -normal;
  }
  return StsvPlane{ normal, -glm::dot(normal, moved[0]) };
}

bool insideBox(const Bounds& box, const glm::dvec3& p)
{
  return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x && p.y <= box.max.y &&
    p.z <= box.max.z;
}

// The construction's invariants, as distances (world units): every outer plane has the light piece on its negative
// side and touches it at its corner, t lies inside every outer plane and beyond the front cap, and the light piece is
// on the near side of the front cap; extrusions run away from the light.
struct Invariants
{
  double lightOutsideOuterPlane = 0.0; // max over corners of the distance (must be <= 0)
  double tangentCornerDistance = 0.0;  // max |distance| of the tangent corner
  double triangleOutside = 0.0;        // max over t's vertices of -distance (outer planes, front cap)
  double lightBeyondFrontCap = 0.0;    // max over corners of the front cap distance
  double extrusionTowardLight = 0.0;   // max over vertices of -(cap normal . extrusion), unclamped volumes
};

void accumulateInvariants(const VolumeCase& c, Invariants& invariants)
{
  for (const Stsv& stsv : c.volumes)
  {
    for (std::size_t i = 0; i < 3; ++i)
    {
      const StsvPlane& plane = stsv.outerPlanes[i];
      for (const glm::dvec3& corner : stsv.lightPiece)
      {
        invariants.lightOutsideOuterPlane = std::max(invariants.lightOutsideOuterPlane, plane.distance(corner));
      }
      invariants.tangentCornerDistance = std::max(invariants.tangentCornerDistance,
        std::abs(plane.distance(stsv.lightPiece[static_cast<std::size_t>(stsv.outerPlaneCorner[i])])));
      for (const glm::dvec3& vertex : c.triangle.vertices)
      {
        invariants.triangleOutside = std::max(invariants.triangleOutside, -plane.distance(vertex));
        invariants.triangleOutside = std::max(invariants.triangleOutside, -stsv.frontCapPlane.distance(vertex));
      }
      if (!stsv.closedVolumeTruncated)
      {
        invariants.extrusionTowardLight = std::max(
          invariants.extrusionTowardLight, -glm::dot(stsv.frontCapPlane.normal, stsv.extrusion[i]));
      }
    }
    for (const glm::dvec3& corner : stsv.lightPiece)
    {
      invariants.lightBeyondFrontCap = std::max(invariants.lightBeyondFrontCap, stsv.frontCapPlane.distance(corner));
    }
  }
}

// 10^6 random points over 50 random cases (20 000 each): near the triangle, between it and the light, and beyond it
// in its shadow (a light point, a triangle point, and beyond, jittered: many points on the shadow's boundary). Each
// point against 24 light samples (16 stratified + the light's corners and edge midpoints) and an opaque triangle, so
// every segment that crosses t is blocked. Any blocked sample of side sigma implies p inside the STSV of side sigma
// (conservativeness); a point of the scene box inside it is inside the closed volume too
// (the back cap lies beyond the box) unless the STSV says its back cap was clamped. Also measured: how tight (empty
// hits, with the front cap and with t's plane as the fourth plane) and what the opposite-side check changes inside
// and outside the volumes.
TEST(StsvVolume, ConservativeOverAMillionRandomPoints)
{
  const auto start = std::chrono::steady_clock::now();
  Random random(3141592);
  const ImageF opaque = opaqueAlpha();
  LightSampleSetSettings settings;
  settings.pattern = LightSamplePattern::Stratified;
  settings.count = 16;
  settings.seed = 7;
  const LightSampleSet set(settings);
  constexpr int kCases = 50;
  constexpr int kPointsPerCase = 20000;
  long long blocked = 0;
  long long notContained = 0;
  long long insidePoints = 0;
  long long emptyHits = 0;
  long long insideWithTrianglePlane = 0;
  long long emptyHitsWithTrianglePlane = 0;
  long long closedChecked = 0;
  long long notInClosedVolume = 0;
  long long ownSideFalse = 0;   // inside STSV_sigma, a sigma sample the paper's test alone calls occluded falsely
  long long otherSideFalse = 0; // inside STSV_sigma, a -sigma sample likewise (only when the light straddles)
  long long outsideFalse = 0;   // in no STSV, a sample likewise
  long long missedByPaperCap = 0; // blocked pairs of fallback STSVs on c's side of the paper's t' plane
  int volumes = 0;
  int straddling = 0;
  int frontCapFallbacks = 0;
  int clamped = 0;
  Invariants invariants;
  int pointIndex = 0;
  for (int caseIndex = 0; caseIndex < kCases; ++caseIndex)
  {
    const CaseKind kind = caseIndex % 10 < 4 ? CaseKind::Free : caseIndex % 10 < 7 ? CaseKind::Close
                                                                                     : CaseKind::Straddling;
    const VolumeCase c = randomVolumeCase(random, kind);
    // A random triangle's plane may cut the light in any kind of case; the Straddling kind always does.
    ASSERT_EQ(c.volumes.size(), kind == CaseKind::Straddling ? 2u : c.volumes.size()) << "case " << caseIndex;
    ASSERT_GE(c.volumes.size(), 1u);
    accumulateInvariants(c, invariants);
    for (const Stsv& stsv : c.volumes)
    {
      ++volumes;
      straddling += stsv.lightStraddlesPlane;
      frontCapFallbacks += stsv.frontCapIsTriangle;
      clamped += stsv.closedVolumeTruncated;
    }
    const auto& t = c.triangle.vertices;
    Bounds triangleBox;
    for (const glm::dvec3& vertex : t)
    {
      triangleBox.extend(vertex);
    }
    for (int k = 0; k < kPointsPerCase; ++k, ++pointIndex)
    {
      double u = uniform(random, 0.0, 1.0);
      double v = uniform(random, 0.0, 1.0);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      const glm::dvec3 onTriangle = pointOn(c.triangle, u, v);
      const glm::dvec3 onLight =
        pointOnAreaLight(c.light, glm::dvec2(uniform(random, 0.0, 1.0), uniform(random, 0.0, 1.0)));
      glm::dvec3 p;
      switch (k % 3)
      {
      case 0:
        p = uniformIn(random, triangleBox.min - glm::dvec3(0.5), triangleBox.max + glm::dvec3(0.5));
        break;
      case 1:
        p = onTriangle + uniform(random, 0.0, 1.0) * (onLight - onTriangle) +
          uniformIn(random, glm::dvec3(-0.05), glm::dvec3(0.05));
        break;
      default:
        p = onLight + uniform(random, 1.0, 4.0) * (onTriangle - onLight) +
          uniformIn(random, glm::dvec3(-0.02), glm::dvec3(0.02));
        break;
      }
      const std::vector<glm::dvec3> samples = samplesWithExtremes(set, c.light, pointIndex);
      const std::vector<bool> occluded = perforatedTriangleOcclusion(c.triangle, opaque, p, samples);
      const std::vector<bool> paperOnly =
        perforatedTriangleOcclusion(c.triangle, opaque, p, samples, StsvOcclusionTest::Paper);
      std::array<bool, 3> blockedOnSide{}; // index side + 1
      for (std::size_t i = 0; i < samples.size(); ++i)
      {
        if (!occluded[i])
        {
          continue;
        }
        ++blocked;
        const int side = triangleSideOf(c.triangle, samples[i]);
        blockedOnSide[static_cast<std::size_t>(side + 1)] = true;
        const Stsv* stsv = volumeOfSide(c, side);
        if (stsv != nullptr && stsv->frontCapIsTriangle &&
          paperFrontCapPlane(c.triangle, stsv->lightPieceCentre).distance(p) < 0.0)
        {
          ++missedByPaperCap;
        }
        if (stsv == nullptr || !stsvContains(*stsv, p))
        {
          ++notContained;
          if (notContained <= 5)
          {
            ADD_FAILURE() << "case " << caseIndex << " point " << p.x << "," << p.y << "," << p.z << " sample " << i
                          << " side " << side << " blocked but outside its STSV";
          }
        }
      }
      bool insideAny = false;
      for (const Stsv& stsv : c.volumes)
      {
        const bool emptyHere = !blockedOnSide[static_cast<std::size_t>(stsv.lightSide + 1)];
        const bool insideOuter = stsv.outerPlanes[0].distance(p) >= 0.0 && stsv.outerPlanes[1].distance(p) >= 0.0 &&
          stsv.outerPlanes[2].distance(p) >= 0.0;
        if (insideOuter && stsv.trianglePlane.distance(p) >= 0.0)
        {
          ++insideWithTrianglePlane;
          emptyHitsWithTrianglePlane += emptyHere;
        }
        if (!stsvContains(stsv, p))
        {
          continue;
        }
        insideAny = true;
        ++insidePoints;
        emptyHits += emptyHere;
        if (insideBox(c.box, p) && !stsv.closedVolumeTruncated)
        {
          ++closedChecked;
          notInClosedVolume += !stsvClosedVolumeContains(stsv, p);
        }
        for (std::size_t i = 0; i < samples.size(); ++i)
        {
          if (paperOnly[i] && !occluded[i])
          {
            (triangleSideOf(c.triangle, samples[i]) == stsv.lightSide ? ownSideFalse : otherSideFalse) += 1;
          }
        }
      }
      if (!insideAny)
      {
        for (std::size_t i = 0; i < samples.size(); ++i)
        {
          outsideFalse += paperOnly[i] && !occluded[i];
        }
      }
    }
  }
  std::cout << "[ measured ] " << kCases * kPointsPerCase << " points, " << volumes << " STSVs (" << straddling
            << " of straddled lights, " << frontCapFallbacks << " with t as front cap, " << clamped
            << " with a truncated closed volume): " << blocked << " blocked (point, sample) pairs, " << notContained
            << " outside their STSV (" << missedByPaperCap
            << " would be with the paper's t' where ShadowLab falls back to t); " << insidePoints << " (point, STSV) inside, " << emptyHits
            << " of them empty hits; with t's plane as the fourth plane " << insideWithTrianglePlane << " inside, "
            << emptyHitsWithTrianglePlane << " empty; closed volume " << notInClosedVolume << " misses of "
            << closedChecked << " box points; paper's test alone, false occlusions: " << ownSideFalse
            << " own side inside, " << otherSideFalse << " other side inside, " << outsideFalse << " outside; "
            << secondsSince(start) << " s\n";
  std::cout << "[ measured ] invariants: light outside an outer plane " << invariants.lightOutsideOuterPlane
            << ", tangent corner off its plane " << invariants.tangentCornerDistance << ", t outside "
            << invariants.triangleOutside << ", light beyond the front cap " << invariants.lightBeyondFrontCap
            << ", extrusion toward the light " << invariants.extrusionTowardLight << "\n";
  EXPECT_EQ(notContained, 0);
  EXPECT_EQ(notInClosedVolume, 0);
  EXPECT_GT(blocked, 1000000); // the points do probe the shadow
  EXPECT_GT(closedChecked, 100000);
  EXPECT_GT(frontCapFallbacks, 0) << "no case exercised the front cap fallback";
  EXPECT_GT(missedByPaperCap, 0) << "the fallback is never needed: the paper's t' was conservative in every case";
  EXPECT_LE(invariants.lightOutsideOuterPlane, 1e-12);
  EXPECT_LE(invariants.tangentCornerDistance, 1e-12);
  EXPECT_LE(invariants.triangleOutside, 1e-12);
  EXPECT_LE(invariants.lightBeyondFrontCap, 1e-12);
  EXPECT_LE(invariants.extrusionTowardLight, 0.0);
  // Inside STSV_sigma no sigma sample can lie between p and t (header, "The gap"): the check changes nothing there.
  EXPECT_EQ(ownSideFalse, 0);
  // Outside every volume the paper's test alone does call samples occluded: the check is what keeps Eq. 1 right
  // for a caller that skips the volume test.
  EXPECT_GT(outsideFalse, 0);
}

// Tightness in the limit: under a point light the STSV is the hard shadow volume. Beyond t's plane, p is inside the
// STSV exactly when the segment to the light crosses t (points within 1e-9 of a plane are left out as ties).
TEST(StsvVolume, PointLightGivesTheHardShadowVolume)
{
  Random random(271828);
  int compared = 0;
  int inside = 0;
  int mismatches = 0;
  for (int caseIndex = 0; caseIndex < 40; ++caseIndex)
  {
    Light light;
    light.type = LightType::Point;
    light.center = glm::dvec3(uniform(random, -1.0, 1.0), uniform(random, 2.5, 4.0), uniform(random, -1.0, 1.0));
    const StsvTriangle triangle = randomTriangle(random,
      glm::dvec3(uniform(random, -0.5, 0.5), uniform(random, 0.8, 1.8), uniform(random, -0.5, 0.5)), 0.8);
    Bounds box;
    box.extend(glm::dvec3(-6.0, 0.0, -6.0));
    box.extend(glm::dvec3(6.0, 2.0, 6.0));
    const std::vector<Stsv> volumes = buildStsvs(triangle, light, box);
    ASSERT_EQ(volumes.size(), 1u);
    const Stsv& stsv = volumes[0];
    const auto& t = triangle.vertices;
    for (int k = 0; k < 5000; ++k)
    {
      const glm::dvec3 p = uniformIn(random, box.min, box.max);
      const double nearest = std::min({ std::abs(stsv.outerPlanes[0].distance(p)),
        std::abs(stsv.outerPlanes[1].distance(p)), std::abs(stsv.outerPlanes[2].distance(p)),
        std::abs(stsv.trianglePlane.distance(p)) });
      if (stsv.trianglePlane.distance(p) <= 0.0 || nearest < 1e-9)
      {
        continue;
      }
      ++compared;
      const std::optional<RayTriangleHit> hit =
        intersectRayTriangle(p, light.center - p, t[0], t[1] - t[0], t[2] - t[0]);
      const bool shadowed = hit && hit->t > 0.0 && hit->t < 1.0;
      inside += stsvContains(stsv, p);
      mismatches += shadowed != stsvContains(stsv, p);
    }
  }
  std::cout << "[ measured ] point light: " << compared << " points beyond t, " << inside << " inside, " << mismatches
            << " where the STSV and the hard shadow disagree\n";
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(inside, 500);
}

// Tightness under a square light: with t at one distance from the centre (so t' = t), each outer plane supports the
// shadow. A point 1e-6 inside the plane, on the line from the tangent corner through the edge's midpoint, is hidden
// from that corner; 1e-6 outside it, no point of the light (33 x 33 grid with its border) is hidden.
TEST(StsvVolume, OuterPlanesTouchTheShadowOfASquareLight)
{
  Random random(1618);
  const ImageF opaque = opaqueAlpha();
  int planes = 0;
  for (int caseIndex = 0; caseIndex < 30; ++caseIndex)
  {
    const Light light = squareLight(glm::dvec3(uniform(random, -1.0, 1.0), 3.0, uniform(random, -1.0, 1.0)),
      uniform(random, 0.3, 2.0), glm::dvec3(uniform(random, -0.3, 0.3), -1.0, uniform(random, -0.3, 0.3)));
    const double radius = uniform(random, 1.5, 2.5);
    std::array<glm::dvec3, 3> v{};
    for (glm::dvec3& vertex : v)
    {
      const glm::dvec3 direction =
        glm::normalize(glm::dvec3(uniform(random, -0.5, 0.5), -1.0, uniform(random, -0.5, 0.5)));
      vertex = light.center + radius * direction;
    }
    if (glm::length(glm::cross(v[1] - v[0], v[2] - v[0])) < 0.05)
    {
      continue;
    }
    const StsvTriangle triangle = makeStsvTriangle(v[0], v[1], v[2], glm::dvec2(0.0), glm::dvec2(1.0, 0.0),
      glm::dvec2(0.0, 1.0));
    Bounds box;
    box.extend(glm::dvec3(-6.0, 0.0, -6.0));
    box.extend(glm::dvec3(6.0, 2.0, 6.0));
    const std::vector<Stsv> volumes = buildStsvs(triangle, light, box);
    if (volumes.size() != 1u)
    {
      continue; // t's plane cuts the light
    }
    const Stsv& stsv = volumes[0];
    ASSERT_FALSE(stsv.frontCapIsTriangle) << "case " << caseIndex; // t' = t: the light is on c's side of it
    for (std::size_t i = 0; i < 3; ++i)
    {
      EXPECT_LT(glm::length(stsv.frontCap[i] - v[static_cast<std::size_t>(stsv.frontCapVertexOfTriangle[i])]), 1e-12);
    }
    std::vector<glm::dvec3> lightPoints;
    for (int y = 0; y <= 32; ++y)
    {
      for (int x = 0; x <= 32; ++x)
      {
        lightPoints.push_back(pointOnAreaLight(light, glm::dvec2(x / 32.0, y / 32.0)));
      }
    }
    for (std::size_t i = 0; i < 3; ++i)
    {
      ++planes;
      const StsvPlane& plane = stsv.outerPlanes[i];
      const glm::dvec3 corner = stsv.lightPiece[static_cast<std::size_t>(stsv.outerPlaneCorner[i])];
      const glm::dvec3 midpoint = 0.5 * (stsv.frontCap[i] + stsv.frontCap[(i + 1) % 3]);
      const glm::dvec3 onPlane = corner + 2.0 * (midpoint - corner);
      EXPECT_LT(std::abs(plane.distance(onPlane)), 1e-12);
      const glm::dvec3 inside = onPlane + 1e-6 * plane.normal;
      const glm::dvec3 outside = onPlane - 1e-6 * plane.normal;
      EXPECT_TRUE(perforatedTriangleOcclusion(triangle, opaque, inside, { corner })[0])
        << "case " << caseIndex << " plane " << i << ": just inside, the tangent corner is not hidden";
      const std::vector<bool> outsideBits = perforatedTriangleOcclusion(triangle, opaque, outside, lightPoints);
      EXPECT_EQ(std::count(outsideBits.begin(), outsideBits.end(), true), 0)
        << "case " << caseIndex << " plane " << i << ": just outside, part of the light is hidden";
    }
  }
  EXPECT_GE(planes, 60);
}

// Fig. 6: the strip 3 4 5 2 3 0 4 1 2 0 closes the volume (every directed edge of its 8 triangles appears once and its
// reverse once) and, with GL's strip rule, every triangle faces outwards; each outer quad lies in its outer plane and
// the back cap in its plane.
TEST(StsvVolume, StripOfFigure6IsClosedAndFacesOutwards)
{
  Random random(577);
  int strips = 0;
  for (int caseIndex = 0; caseIndex < 300; ++caseIndex)
  {
    const VolumeCase c = randomVolumeCase(random, static_cast<CaseKind>(caseIndex % 3));
    for (const Stsv& stsv : c.volumes)
    {
      if (stsv.closedVolumeTruncated)
      {
        continue;
      }
      ++strips;
      const std::array<glm::dvec3, 10> strip = stsvStrip(stsv);
      glm::dvec3 interior(0.0);
      for (std::size_t i = 0; i < 3; ++i)
      {
        interior += stsv.frontCap[i] + stsv.backCap[i];
      }
      interior /= 6.0;
      std::map<std::pair<int, int>, int> directedEdges;
      for (int k = 0; k < 8; ++k)
      {
        std::array<int, 3> corner{ kStsvStripOrder[static_cast<std::size_t>(k)],
          kStsvStripOrder[static_cast<std::size_t>(k + 1)], kStsvStripOrder[static_cast<std::size_t>(k + 2)] };
        std::array<glm::dvec3, 3> position{ strip[static_cast<std::size_t>(k)], strip[static_cast<std::size_t>(k + 1)],
          strip[static_cast<std::size_t>(k + 2)] };
        if (k % 2 == 1)
        {
          std::swap(corner[0], corner[1]);
          std::swap(position[0], position[1]);
        }
        for (int e = 0; e < 3; ++e)
        {
          ++directedEdges[{ corner[static_cast<std::size_t>(e)], corner[static_cast<std::size_t>((e + 1) % 3)] }];
        }
        const glm::dvec3 normal = glm::cross(position[1] - position[0], position[2] - position[0]);
        EXPECT_GT(glm::dot(normal, position[0] - interior), 0.0)
          << "case " << caseIndex << " strip triangle " << k << " faces inwards";
      }
      for (const auto& [edge, count] : directedEdges)
      {
        EXPECT_EQ(count, 1) << "edge " << edge.first << "->" << edge.second;
        EXPECT_EQ(directedEdges.count({ edge.second, edge.first }), 1u) << "edge " << edge.first << "->" << edge.second;
      }
      const double scale = glm::length(c.box.max - c.box.min);
      for (std::size_t i = 0; i < 3; ++i)
      {
        const std::size_t next = (i + 1) % 3;
        for (const glm::dvec3& corner : { stsv.frontCap[i], stsv.frontCap[next], stsv.backCap[i], stsv.backCap[next] })
        {
          EXPECT_LT(std::abs(stsv.outerPlanes[i].distance(corner)), 1e-12 * scale);
        }
        EXPECT_LT(std::abs(stsv.backCapPlane.distance(stsv.backCap[i])), 1e-12 * scale);
      }
    }
  }
  EXPECT_GT(strips, 250);
}

// ---- Closed form -------------------------------------------------------------------------------------------------

// The visible fraction of a square light (side lightSize, height lightHeight, centred over the origin, facing down,
// edges along x and z) from ground point (x, 0, z) past the horizontal rectangle [x0, x1] x [z0, z1] at height
// occluderHeight: the rectangle projected through the point onto the light plane (scaled by lightHeight /
// occluderHeight about it) overlaps the light in a rectangle. For a centred square it is tests/support's
// parallelSquaresVisibility (gpu_tests only), the same formula.
double rectangleOccluderVisibility(double lightSize, double lightHeight, double x0, double x1, double z0, double z1,
  double occluderHeight, double x, double z)
{
  const double scale = lightHeight / occluderHeight;
  const auto overlap = [&](double low, double high, double at) {
    const double a = at + (low - at) * scale;
    const double b = at + (high - at) * scale;
    return std::max(0.0, std::min(b, 0.5 * lightSize) - std::max(a, -0.5 * lightSize));
  };
  return 1.0 - overlap(x0, x1, x) * overlap(z0, z1, z) / (lightSize * lightSize);
}

// An opaque quad (alpha all 1, two triangles) at height 1 under a square light of side 1 at height 3: the fraction of
// 256 x 256 light points (cell centres, the light's own mapping pointOnAreaLight) left visible through both
// triangles' STSVs, at 17 x 17 ground points, against the closed form. Counting cell centres in an interval errs by at
// most one cell per axis, so |V - V_exact| <= 2/256 + 1/256^2. The same with a texture whose left half is opaque and
// right half a hole (Eq. 4-5 must map u along x): the closed form of the rectangle x in [-1/2, 0].
TEST(StsvClosedForm, OpaqueQuadUnderASquareLight)
{
  const auto start = std::chrono::steady_clock::now();
  constexpr double kLightSize = 1.0;
  constexpr double kLightHeight = 3.0;
  constexpr double kQuad = 1.0;
  constexpr double kQuadHeight = 1.0;
  constexpr int kGrid = 256;
  const Light light = squareLight(glm::dvec3(0.0, kLightHeight, 0.0), kLightSize, glm::dvec3(0.0, -1.0, 0.0));
  std::vector<glm::dvec3> samples;
  for (int j = 0; j < kGrid; ++j)
  {
    for (int i = 0; i < kGrid; ++i)
    {
      samples.push_back(pointOnAreaLight(light, glm::dvec2((i + 0.5) / kGrid, (j + 0.5) / kGrid)));
    }
  }
  const double h = 0.5 * kQuad;
  const glm::dvec3 corner00(-h, kQuadHeight, -h), corner10(h, kQuadHeight, -h), corner11(h, kQuadHeight, h),
    corner01(-h, kQuadHeight, h);
  const std::vector<StsvTriangle> triangles{
    makeStsvTriangle(corner00, corner10, corner11, glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 1)),
    makeStsvTriangle(corner00, corner11, corner01, glm::dvec2(0, 0), glm::dvec2(1, 1), glm::dvec2(0, 1)),
  };
  Bounds box;
  box.extend(glm::dvec3(-3.0, 0.0, -3.0));
  box.extend(glm::dvec3(3.0, kQuadHeight, 3.0));
  std::vector<std::vector<Stsv>> volumes;
  for (const StsvTriangle& triangle : triangles)
  {
    volumes.push_back(buildStsvs(triangle, light, box));
    ASSERT_EQ(volumes.back().size(), 1u);
  }
  ImageF leftHalf(2, 1, 1, 1.0f);
  leftHalf.at(1, 0) = 0.0f;
  const double bound = 2.0 / kGrid + 1.0 / (kGrid * kGrid);
  for (const bool half : { false, true })
  {
    const ImageF alpha = half ? leftHalf : opaqueAlpha();
    double maxError = 0.0;
    int penumbra = 0;
    for (int zi = 0; zi <= 16; ++zi)
    {
      for (int xi = 0; xi <= 16; ++xi)
      {
        const double x = -1.2 + 0.15 * xi;
        const double z = -1.2 + 0.15 * zi;
        const glm::dvec3 p(x, 0.0, z);
        std::vector<bool> hidden(samples.size(), false);
        for (std::size_t t = 0; t < triangles.size(); ++t)
        {
          for (const Stsv& stsv : volumes[t])
          {
            const std::vector<bool> bits = stsvOcclusion(stsv, triangles[t], alpha, p, samples);
            for (std::size_t i = 0; i < bits.size(); ++i)
            {
              hidden[i] = hidden[i] || bits[i];
            }
          }
        }
        const double visibility =
          1.0 - double(std::count(hidden.begin(), hidden.end(), true)) / double(samples.size());
        const double exact = rectangleOccluderVisibility(
          kLightSize, kLightHeight, -h, half ? 0.0 : h, -h, h, kQuadHeight, x, z);
        penumbra += exact > 0.0 && exact < 1.0;
        maxError = std::max(maxError, std::abs(visibility - exact));
        EXPECT_LE(std::abs(visibility - exact), bound)
          << (half ? "left half opaque" : "opaque") << " ground " << x << "," << z << " STSV " << visibility
          << " closed form " << exact;
      }
    }
    std::cout << "[ measured ] " << (half ? "half-opaque" : "opaque") << " quad: max |V - closed form| " << maxError
              << " (bound " << bound << "), " << penumbra << " of 289 points in the penumbra\n";
    EXPECT_GT(penumbra, 50);
  }
  std::cout << "[ measured ] " << secondsSince(start) << " s\n";
}

// ---- Hard cases ---------------------------------------------------------------------------------------------------

// Points on the perforated triangle itself (a fence pixel): exactly on it, and as a float G-buffer stores them (a few
// 1e-8 off the plane). t never shadows them (it is skipped within kStsvOnPlaneRelative of its plane, and e is never
// divided by when 0). Without the skip, the float points below the plane are hidden by their own texel.
TEST(StsvHardCases, PointsOnThePerforatedTriangle)
{
  Random random(99);
  const ImageF opaque = opaqueAlpha();
  const Light light = squareLight(glm::dvec3(0.3, 3.0, 0.2), 0.5, glm::dvec3(-0.3, -3.0, -0.2));
  std::vector<glm::dvec3> samples;
  for (int i = 0; i < 64; ++i)
  {
    samples.push_back(pointOnAreaLight(light, glm::dvec2((i % 8 + 0.5) / 8.0, (i / 8 + 0.5) / 8.0)));
  }
  int selfShadowedWithoutSkip = 0;
  int points = 0;
  for (int caseIndex = 0; caseIndex < 20; ++caseIndex)
  {
    const StsvTriangle triangle = randomTriangle(random, glm::dvec3(0.0, 1.0, 0.0), 1.0);
    for (int k = 0; k < 200; ++k)
    {
      double u = uniform(random, 0.0, 1.0);
      double v = uniform(random, 0.0, 1.0);
      if (u + v > 1.0)
      {
        u = 1.0 - u;
        v = 1.0 - v;
      }
      const glm::dvec3 exact = k == 0 ? triangle.vertices[0] : pointOn(triangle, u, v);
      const glm::dvec3 stored = glm::dvec3(glm::vec3(exact)); // the G-buffer's float position
      for (const glm::dvec3& p : { exact, stored })
      {
        ++points;
        const StsvPointTransform transform = stsvPointTransform(triangle, p, stsvOnPlaneDistance(triangle));
        EXPECT_TRUE(transform.onPlane) << "e " << transform.planeOffset.z;
        const std::vector<bool> bits = perforatedTriangleOcclusion(triangle, opaque, p, samples);
        EXPECT_EQ(std::count(bits.begin(), bits.end(), true), 0);
        const StsvPointTransform unskipped = stsvPointTransform(triangle, p, 0.0);
        for (const glm::dvec3& s : samples)
        {
          const StsvSampleEvaluation evaluation = evaluateStsvSample(
            triangle, unskipped, opaque, p, s, StsvOcclusionTest::PaperAndOppositeSides);
          EXPECT_TRUE(std::isfinite(evaluation.homogeneousBarycentric.x) || unskipped.onPlane);
          selfShadowedWithoutSkip += evaluation.occluded;
        }
      }
    }
  }
  // A receiver just under the triangle (a ground touching a fence) is not skipped.
  const StsvTriangle triangle = makeStsvTriangle(glm::dvec3(-1, 1, -1), glm::dvec3(1, 1, -1), glm::dvec3(0, 1, 1),
    glm::dvec2(0), glm::dvec2(1, 0), glm::dvec2(0, 1));
  EXPECT_FALSE(stsvPointTransform(triangle, glm::dvec3(0.0, 1.0 - 1e-3, 0.0), stsvOnPlaneDistance(triangle)).onPlane);
  const std::vector<bool> underneath = perforatedTriangleOcclusion(triangle, opaque, glm::dvec3(0.0, 1.0 - 1e-3, 0.0),
    samples);
  EXPECT_EQ(std::count(underneath.begin(), underneath.end(), true), 64);
  std::cout << "[ measured ] " << points << " points on perforated triangles: none shadowed by their own triangle; "
            << selfShadowedWithoutSkip << " (point, sample) pairs would be without the skip\n";
  EXPECT_GT(selfShadowedWithoutSkip, 0);
}

// The samples on a ray tracer's side for the hard cases: per point, the bits of every perforated triangle OR-ed, the
// way the STSV pass would find them (per STSV, its own side's samples), and the ray tracer's bits (open segment, alpha
// filter), with the pairs within 1e-9 of a decision counted as ambiguous.
struct HardCaseBits
{
  long long pairs = 0;
  long long occluded = 0;
  long long mismatches = 0;
  long long ambiguousPairs = 0;
  long long falseWithoutCheck = 0;      // the STSV pass, paper's test alone, own side's samples
  long long falseWithoutCheckAll = 0;   // the same evaluating all N samples in every STSV containing p
  long long falseWithoutVolume = 0;     // Eq. 1 alone (no volume test), paper's test alone
  long long insideAnyStsv = 0;          // points
};

void accumulateHardCase(const std::vector<StsvTriangle>& triangles, const std::vector<std::vector<Stsv>>& volumes,
  const ImageF& alpha, const glm::dvec3& p, const std::vector<glm::dvec3>& samples, HardCaseBits& bits)
{
  std::vector<bool> stsvBits(samples.size(), false);
  std::vector<bool> paperBits(samples.size(), false);
  std::vector<bool> paperAllBits(samples.size(), false);
  std::vector<bool> noVolumeBits(samples.size(), false);
  bool inside = false;
  const auto orInto = [](std::vector<bool>& into, const std::vector<bool>& from) {
    for (std::size_t i = 0; i < from.size(); ++i)
    {
      into[i] = into[i] || from[i];
    }
  };
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    for (const Stsv& stsv : volumes[t])
    {
      inside = inside || stsvContains(stsv, p);
      orInto(stsvBits, stsvOcclusion(stsv, triangles[t], alpha, p, samples));
      orInto(paperBits, stsvOcclusion(stsv, triangles[t], alpha, p, samples, StsvOcclusionTest::Paper));
      orInto(paperAllBits, stsvOcclusion(stsv, triangles[t], alpha, p, samples, StsvOcclusionTest::Paper, false));
    }
    orInto(noVolumeBits, perforatedTriangleOcclusion(triangles[t], alpha, p, samples, StsvOcclusionTest::Paper));
  }
  bits.insideAnyStsv += inside;
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    ++bits.pairs;
    bool traced = false;
    bool tie = false;
    for (const StsvTriangle& triangle : triangles)
    {
      traced = traced || rayTracedOccluded(triangle, alpha, p, samples[i]);
      tie = tie || ambiguous(triangle, &alpha, p, samples[i], 1e-9);
    }
    bits.occluded += traced;
    bits.falseWithoutCheck += paperBits[i] && !traced;
    bits.falseWithoutCheckAll += paperAllBits[i] && !traced;
    bits.falseWithoutVolume += noVolumeBits[i] && !traced;
    if (tie)
    {
      ++bits.ambiguousPairs;
      continue;
    }
    bits.mismatches += stsvBits[i] != traced;
  }
}

std::vector<glm::dvec3> stratifiedSamples(const Light& light, int count, int pointIndex)
{
  LightSampleSetSettings settings;
  settings.pattern = LightSamplePattern::Stratified;
  settings.count = count;
  settings.seed = 11;
  const LightSampleSet set(settings);
  std::vector<glm::dvec3> samples;
  for (int i = 0; i < count; ++i)
  {
    samples.push_back(set.point(light, pointIndex % 512, pointIndex / 512, i));
  }
  return samples;
}

// The fence dataset (a horizontal fence quad at y = 1 under a tilted square light at y = 3) with a plate of receivers
// 0.02 above the fence, between it and the light, and a layer of points beyond the light. On the plate and under the
// fence the STSV pass equals the ray tracer (16 samples, fence alpha) on every unambiguous pair. Between the fence
// and the light a sample can never lie between p and the plane (the light is farther from it), so even the paper's
// test alone finds no false shadow there (measured 0): the expected "points between the fence and the light are
// shadowed falsely" needs a point farther from the plane than a sample, e.g. beyond the light, where Eq. 1 without the
// check does hide samples, and where no STSV reaches.
TEST(StsvHardCases, PlateJustAboveTheFence)
{
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = loadScene(std::filesystem::path(SL_SOURCE_DIR) / "datasets" / "fence" / "scene.json");
  const Light& light = scene.lights.at(0);
  const std::vector<StsvTriangle> triangles = perforatedTriangles(scene);
  ASSERT_EQ(triangles.size(), 2u);
  const ImageF& alpha = scene.objects.at(triangles[0].objectIndex).alphaTexture.alpha;
  const Bounds box = scene.bounds();
  std::vector<std::vector<Stsv>> volumes;
  for (const StsvTriangle& triangle : triangles)
  {
    volumes.push_back(buildStsvs(triangle, light, box));
    ASSERT_EQ(volumes.back().size(), 1u);
  }
  HardCaseBits plate;
  HardCaseBits ground;
  int pointIndex = 0;
  for (int zi = 0; zi <= 40; ++zi)
  {
    for (int xi = 0; xi <= 40; ++xi, ++pointIndex)
    {
      const double x = -1.1 + 2.2 * xi / 40.0;
      const double z = -0.8 + 1.6 * zi / 40.0;
      accumulateHardCase(triangles, volumes, alpha, glm::dvec3(x, 1.02, z), stratifiedSamples(light, 16, pointIndex),
        plate);
      accumulateHardCase(triangles, volumes, alpha, glm::dvec3(1.5 * x, 0.0, 1.5 * z),
        stratifiedSamples(light, 16, pointIndex + 5000), ground);
    }
  }
  // Beyond the light: p = Y + (Y - X) / 2 for a light point Y and a fence point X, with Y itself among the samples.
  Random random(4);
  HardCaseBits beyond;
  for (int k = 0; k < 400; ++k)
  {
    const glm::dvec3 onLight = pointOnAreaLight(light, glm::dvec2(uniform(random, 0.0, 1.0), uniform(random, 0.0, 1.0)));
    const glm::dvec3 onFence(uniform(random, -1.0, 1.0), 1.0, uniform(random, -0.7, 0.7));
    const glm::dvec3 p = onLight + 0.5 * (onLight - onFence);
    std::vector<glm::dvec3> samples = stratifiedSamples(light, 16, k + 10000);
    samples.push_back(onLight);
    accumulateHardCase(triangles, volumes, alpha, p, samples, beyond);
  }
  for (const auto& [name, bits] : { std::pair<const char*, const HardCaseBits&>{ "plate y = 1.02", plate },
         { "ground under the fence", ground }, { "beyond the light", beyond } })
  {
    std::cout << "[ measured ] fence, " << name << ": " << bits.pairs << " pairs, " << bits.occluded
              << " occluded by the ray tracer, " << bits.mismatches << " STSV mismatches, " << bits.ambiguousPairs
              << " ambiguous; " << bits.insideAnyStsv << " points inside an STSV; paper's test alone: "
              << bits.falseWithoutCheck << " false (STSV pass), " << bits.falseWithoutVolume
              << " false (Eq. 1 without the volume)\n";
    EXPECT_EQ(bits.mismatches, 0) << name;
    EXPECT_LE(bits.ambiguousPairs, bits.pairs / 1000) << name;
    EXPECT_EQ(bits.falseWithoutCheck, 0) << name;
  }
  std::cout << "[ measured ] " << secondsSince(start) << " s\n";
  EXPECT_EQ(plate.occluded, 0);           // nothing between the plate and the light
  EXPECT_EQ(plate.falseWithoutVolume, 0); // and no sample between the plate and the fence's plane
  EXPECT_GT(ground.occluded, ground.pairs / 10);
  EXPECT_EQ(beyond.occluded, 0);
  EXPECT_EQ(beyond.insideAnyStsv, 0);
  EXPECT_GT(beyond.falseWithoutVolume, 100); // Eq. 1 without the check and without the volume: false shadows
}

// A light straddling the triangle's plane: a vertical fence (plane x = 0, two perforated triangles, fence alpha) under
// a square light of side 2 centred at x = 0.2, y = 3. Each triangle gets two STSVs, one per side, each with the light
// piece on its side; the pieces' areas add up to the light's. On ground points and random points below the light,
// every blocked sample of side sigma lies in STSV_sigma, and the STSV pass (each STSV its own side's samples) equals
// the ray tracer on 64 samples; samples on the side away from the light's centre are blocked too (what the paper's
// single STSV per triangle, built from the centre, misses: the "single light sample artifact", Forest et al. 2009 §6). Three fences:
// under the light (z in [-1, 1], top at y = 1.5); beside it and reaching above it (z in [1.1, 3.1], top at y = 4); and
// through it (z in [-1, 1], top at y = 4: the fence cuts the light's square, its STSVs are the half-spaces beyond its
// plane and say closedVolumeTruncated). Reaching above the light, a point can be lit by a sample s of its own side
// lying between it and the fence's plane, the line from p through s meeting the fence above the light: Eq. 1 without
// the check hides s (beside: outside every STSV; through: inside the other side's STSV, whose samples are blocked, so
// a pass that evaluated all N samples in every STSV would hide s). The own-side rule and the check each prevent it.
TEST(StsvHardCases, LightStraddlingTheTrianglePlane)
{
  const auto start = std::chrono::steady_clock::now();
  const Light light = squareLight(glm::dvec3(0.2, 3.0, 0.0), 2.0, glm::dvec3(0.0, -1.0, 0.0));
  const ImageF fence = makeFenceAlpha();
  struct Fence
  {
    const char* name;
    double z0;
    double top;
  };
  for (const Fence& variant : { Fence{ "under", -1.0, 1.5 }, Fence{ "beside", 1.1, 4.0 }, Fence{ "through", -1.0, 4.0 } })
  {
    const double z0 = variant.z0;
    const double top = variant.top;
    const glm::dvec3 a(0.0, 0.5, z0), b(0.0, 0.5, z0 + 2.0), c(0.0, top, z0 + 2.0), d(0.0, top, z0);
    const std::vector<StsvTriangle> triangles{
      makeStsvTriangle(a, b, c, glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(1, 0.5)),
      makeStsvTriangle(a, c, d, glm::dvec2(0, 0), glm::dvec2(1, 0.5), glm::dvec2(0, 0.5)),
    };
    Bounds box;
    box.extend(glm::dvec3(-4.0, 0.0, -4.0));
    box.extend(glm::dvec3(4.0, top, 4.0));
    std::vector<std::vector<Stsv>> volumes;
    for (const StsvTriangle& triangle : triangles)
    {
      volumes.push_back(buildStsvs(triangle, light, box));
      ASSERT_EQ(volumes.back().size(), 2u);
      double area = 0.0;
      for (const Stsv& stsv : volumes.back())
      {
        EXPECT_TRUE(stsv.lightStraddlesPlane);
        for (const glm::dvec3& corner : stsv.lightPiece)
        {
          EXPECT_GE(stsv.lightSide * glm::dot(triangle.normal, corner - triangle.vertices[0]), -1e-12);
        }
        glm::dvec3 twiceArea(0.0);
        for (std::size_t k = 0; k < stsv.lightPiece.size(); ++k)
        {
          twiceArea += glm::cross(stsv.lightPiece[k], stsv.lightPiece[(k + 1) % stsv.lightPiece.size()]);
        }
        area += 0.5 * glm::length(twiceArea);
      }
      EXPECT_NEAR(area, light.size * light.size, 1e-12);
      if (std::string(variant.name) == "through")
      {
        EXPECT_TRUE(volumes.back()[0].closedVolumeTruncated && volumes.back()[1].closedVolumeTruncated);
      }
      EXPECT_NE(volumes.back()[0].lightSide, volumes.back()[1].lightSide);
    }
    Random random(8);
    HardCaseBits bits;
    long long notContained = 0;
    long long blockedAwayFromCentre = 0;
    for (int k = 0; k < 6000; ++k)
    {
      // A 40 x 40 ground grid (cell centres: none in the fence's plane x = 0), then random points below the light.
      const glm::dvec3 p = k < 1600
        ? glm::dvec3(-3.0 + 6.0 * (k % 40 + 0.5) / 40.0, 0.0, -3.0 + 6.0 * (k / 40 + 0.5) / 40.0)
        : uniformIn(random, glm::dvec3(-2.5, 0.0, z0 - 0.5), glm::dvec3(2.5, 2.9, z0 + 2.5));
      const std::vector<glm::dvec3> samples = stratifiedSamples(light, 64, k);
      accumulateHardCase(triangles, volumes, fence, p, samples, bits);
      for (std::size_t t = 0; t < triangles.size(); ++t)
      {
        const int centreSide = triangleSideOf(triangles[t], light.center);
        const std::vector<bool> occluded = perforatedTriangleOcclusion(triangles[t], fence, p, samples);
        for (std::size_t i = 0; i < samples.size(); ++i)
        {
          if (!occluded[i])
          {
            continue;
          }
          const int side = triangleSideOf(triangles[t], samples[i]);
          blockedAwayFromCentre += side != centreSide;
          const auto stsv = std::find_if(volumes[t].begin(), volumes[t].end(),
            [&](const Stsv& volume) { return volume.lightSide == side; });
          notContained += stsv == volumes[t].end() || !stsvContains(*stsv, p);
        }
      }
    }
    std::cout << "[ measured ] straddling light, fence " << variant.name << ": " << bits.pairs << " pairs, "
              << bits.occluded << " occluded by the ray tracer (" << blockedAwayFromCentre
              << " by samples on the side away from the light's centre), " << bits.mismatches << " STSV mismatches, "
              << bits.ambiguousPairs << " ambiguous, " << notContained
              << " blocked outside their STSV; paper's test alone: " << bits.falseWithoutCheck << " false (own side), "
              << bits.falseWithoutCheckAll << " false (all samples in every STSV), " << bits.falseWithoutVolume
              << " false (no volume)\n";
    EXPECT_EQ(notContained, 0) << variant.name;
    EXPECT_EQ(bits.mismatches, 0) << variant.name;
    EXPECT_LE(bits.ambiguousPairs, bits.pairs / 1000) << variant.name;
    EXPECT_GT(bits.occluded, bits.pairs / 100) << variant.name;
    EXPECT_GT(blockedAwayFromCentre, 1000) << variant.name;
    EXPECT_EQ(bits.falseWithoutCheck, 0) << variant.name;
    if (std::string(variant.name) == "beside")
    {
      EXPECT_GT(bits.falseWithoutVolume, 0) << "no false shadow from Eq. 1 without the check";
    }
    if (std::string(variant.name) == "through")
    {
      EXPECT_GT(bits.falseWithoutCheckAll, 0) << "no false shadow from an all-samples pass without the check";
    }
  }
  std::cout << "[ measured ] " << secondsSince(start) << " s\n";
}

} // namespace
} // namespace sl
