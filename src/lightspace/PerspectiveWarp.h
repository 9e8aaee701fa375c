// Perspective warping of a focused shadow map (survey §4.2): PSM, LiSPSM and TSM as one warp P with its free
// parameter n, the distance from P's projection centre to its near plane (survey Fig. 9).
//
// P looks along the view direction projected onto the light's image plane (LiSPSM's light- and view-aligned
// frame), so a directional light stays directional after it: every light ray keeps one shadow-map texel column and
// the map still stores linear depth along the light axis (bias and comparisons keep their meaning). In light view
// coordinates, with u the distance past the near side of the focused body B along P's axis (B spans u in [0, L])
// and p the lateral offset from the eye:
//   W = 1 + u / n,   t = (1/n + 1/L) u / W,   s = p / W     (t in [0, 1] over B; n -> infinity: uniform)
// which is the survey's s(z) = C (1 - n / (z - z_n + n)), C = (z_f - z_n + n) / (z_f - z_n), for view ⟂ light.
// Written with 1/n rather than n, n -> infinity (γ -> 0) is the uniform map with finite matrices.
//
// The rules for n (z_n, z_f: the nearest and farthest eye depth of the visible receivers, the eye frustum after
// focusing; γ the angle between the view and light directions):
//   psm     n = z_n / sin γ                        (the viewer's own near plane, SD02)
//   lispsm  n = (z_n + sqrt(z_n z_f)) / sin γ       (survey §4.2.2: n_opt, and LiSPSM's falloff n_opt / sin γ)
//   tsm     n = L / 3 / sin γ                       (MT04's 80 % rule: B's middle lands on the map's 80 % line)
// warp_n > 0 replaces the rule's n (no falloff). The projection centre lies at u = -n < 0, outside B, so the
// depth order along a light ray never flips; point, spot and area lights (LiSPSM in the light's post-perspective
// space) are refused.
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <string>

namespace sl
{

enum class WarpKind
{
  None,
  Psm,
  Lispsm,
  Tsm
};

const char* warpName(WarpKind kind);

// Throws InputError naming `--set warp=...` unless `kind` is None or the light is directional (LiSPSM in a point,
// spot or area light's post-perspective space is not implemented). The renderer asks before any GL; the focus again.
void requireWarpableLight(WarpKind kind, LightType lightType);

struct WarpSettings
{
  WarpKind kind = WarpKind::None;
  double n = 0.0; // warp_n: > 0 replaces the rule's n; 0: the rule's
};

// What the focus applied, for the bias, the stats and the tests.
struct PerspectiveWarp
{
  WarpKind kind = WarpKind::None;
  double n = 0.0;          // the n used (infinity when the warp degraded to uniform)
  double nOpt = 0.0;       // LiSPSM's n_opt / sin γ for the same view, whatever the kind
  double gammaDeg = 90.0;  // angle between view and light directions
  double zNear = 0.0;      // eye depth range of the visible receivers
  double zFar = 0.0;
  double nearDistance = 0.0; // P's near and far planes, distances from its projection centre (n and n + L)
  double farDistance = 0.0;
  bool active() const { return kind != WarpKind::None; }
};

// P's free parameter for `kind` (None: infinity). sinGamma below 1e-9 (view ∥ light) gives infinity: the warp
// degrades to the uniform map (survey §4.2.2).
double warpParameter(WarpKind kind, double zNear, double zFar, double bodyLength, double sinGamma);
// LiSPSM's n_opt = z_n + sqrt(z_n z_f) (survey §4.2.2, view ⟂ light).
double lispsmOptimalN(double zNear, double zFar);

// The warp's rows in the frame (p, u) described above: clip (X, T, W) = rows . (p, u, 1), with the map's t = T / W.
// Used by the focus (LightView.cpp) and by the closed-form tests.
struct WarpRows
{
  glm::dvec3 x;
  glm::dvec3 t;
  glm::dvec3 w;
};
WarpRows warpRows(double n, double bodyLength);

// The survey's Fig. 12 closed forms for view ⟂ light at eye depth z (n -> infinity: uniform).
double closedFormWarpT(double z, double zNear, double zFar, double n);
double closedFormWarpAliasing(double z, double zNear, double zFar, double n); // dp/ds = (1/z) dz/ds

} // namespace sl
