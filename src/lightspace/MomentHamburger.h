// CPU twin (double precision) of shaders/common/MomentHamburger.glsl: Hamburger 4MSM (Peters & Klein 2015,
// Algorithm 3), shared by msm and msmsoft. Moved here unchanged from techniques/msm (README.md there derives it).
#pragma once

#include <glm/glm.hpp>

namespace sl
{

// MSM Alg. 3 (Hamburger 4MSM) in double precision, step by step as common/MomentHamburger.glsl computes it.
struct MsmReconstruction
{
  glm::dvec4 biasedMoments{ 0.0 }; // b' = (1 - alpha) b + alpha (0.5, 0.5, 0.5, 0.5)
  double pivot2 = 0.0;             // D22 = b2' - b1'^2 (the biased variance)
  double pivot3 = 0.0;             // D33 = det(B) / D22, the last pivot of LDL^T: ~0 where B is near singular
  glm::dvec3 polynomial{ 0.0 };    // c: B c = (1, z_f, z_f^2)
  double supportNear = 0.0;        // z_2 <= z_3, the roots of c1 + c2 z + c3 z^2
  double supportFar = 0.0;
  glm::dvec3 weights{ 0.0 };       // of z_f, z_2, z_3 in the three-point distribution with moments 1, b1', b2'
  double shadowIntensity = 0.0;    // G, clamped to [0, 1]
};
MsmReconstruction msmHamburger4(const glm::dvec4& moments, double momentBias, double fragmentDepth);

} // namespace sl
