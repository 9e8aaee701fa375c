// Hamburger 4MSM (Peters & Klein 2015, Algorithm 3, in the form of the authors' shader code as public ports give it;
// steps 2-4 are the m = 4 case of Peters et al. 2017 (JCGT), Alg. 1; msm/README.md, Sources), shared by msm
// (msm/MsmVisibility.glsl) and msmsoft (msmsoft/MsmSoftVisibility.glsl). Needs the technique's moment_bias parameter
// (uniform param_moment_bias, alpha). Steps 1-4 as MsmVisibility.glsl's header lists them.
struct MsmReconstruction
{
  float intensity; // G, unclamped
  float z2;        // support points
  float z3;
  float d33;       // last pivot
};

// MSM Alg. 3 on the moments b (before the bias) at the receiver's depth z_f. CPU mirror: msmHamburger4
// (src/lightspace/MomentHamburger.cpp).
MsmReconstruction hamburger4Msm(vec4 moments, float zf)
{
  // Step 1: the moment bias.
  vec4 b = mix(moments, vec4(0.5), param_moment_bias);
  // Step 2: LDL^T of the Hankel matrix, only its non-trivial entries (D11 = 1, L21 = b1, L31 = b2).
  // D22, the variance of the biased depths: >= alpha / 4 in exact arithmetic (the bias mixes in mass alpha / 2 at
  // 0 and at 1); where the box holds one depth and the bias is lost in float, rounding leaves it at 0 or below and
  // l32 would be 0 / 0. Floored at 1e-12 as D33 (the twin alike); moment_bias >= 1e-6 keeps it above the rounding.
  float d22 = max(b.y - b.x * b.x, 1e-12);
  float l32d22 = b.z - b.x * b.y;
  float l32 = l32d22 / d22;
  // The third pivot, det(B) / D22: > 0 for alpha > 0 in exact arithmetic; float rounding can make it 0 or less,
  // and 1 / 0 would reach the support points as inf - inf. Floored at 1e-12 (the twin alike).
  float d33 = max((b.w - b.y * b.y) - l32d22 * l32, 1e-12);
  vec3 c = vec3(1.0, zf, zf * zf);
  c.y -= b.x;                // forward substitution, L c' = (1, z_f, z_f^2)
  c.z -= b.y + l32 * c.y;
  c.y /= d22;                // D c'' = c'
  c.z /= d33;
  c.y -= l32 * c.z;          // backward substitution, L^T c = c''
  c.x -= c.y * b.x + c.z * b.y;
  // Step 3: the other two support points, the roots of c1 + c2 z + c3 z^2. The authors' code divides by c3
  // (p = c2 / c3, q = c1 / c3); where B is near singular c3 can round to ~0 in float and one root runs off to
  // infinity while the other cancels. The same roots by the stable form (the large one from
  // -(c2 + sign(c2) sqrt(disc)) / 2, the other by Vieta), clamped to +-1e6 (a support point that far from [0, 1]
  // carries no weight): finite throughout.
  // The discriminant is >= 0 in exact arithmetic (B positive definite); rounding can push it below.
  float root = sqrt(max(c.y * c.y - 4.0 * c.x * c.z, 0.0));
  float large = -0.5 * (c.y + (c.y < 0.0 ? -root : root));
  float rootA = clamp(large / c.z, -1e6, 1e6);
  float rootB = clamp(c.x / large, -1e6, 1e6);
  float z2 = min(rootA, rootB);
  float z3 = max(rootA, rootB);
  // Step 4: sum the weights of the support points in front of z_f.
  float intensity;
  if (zf <= z2)
  {
    intensity = 0.0;
  }
  else if (zf <= z3)
  {
    intensity = (zf * z3 - b.x * (zf + z3) + b.y) / ((z3 - z2) * (zf - z2));
  }
  else
  {
    intensity = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((zf - z2) * (zf - z3));
  }
  return MsmReconstruction(intensity, z2, z3, d33);
}
