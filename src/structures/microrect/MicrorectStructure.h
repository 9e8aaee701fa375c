// Microrects (Schwarz & Stamminger 2008, SS08 §5.2, Figs. 4-6): per shadow-map level i >= 1 one
// micro-occluder per texel whose extent is a rectangle of level-0 texels (containing its reference point
// (2^i x, 2^i y) and no other) and whose depth is the min over the level-(i-1) microrects it absorbed. Definition,
// proofs and the CPU twin: lightspace/Microrects.h. Stored (§5.2) as two N x N atlases in the HSM mip-map
// layout (levels 1..L): extents RGBA16UI (x0, y0, x1, y1), depths R32F; level 0 is the shadow map. Built by
// vtkSLMicrorectPass (stage microrects); GLSL lookup: shaders/common/MicrorectLookup.glsl (microrectAt). No
// parameters.
#pragma once

#include "frame/TechniqueDescriptor.h"
#include "structures/LightSpaceStructure.h"

#include <vector>

namespace sl
{

const LightSpaceStructure& microrectStructure();

// What the build shader (structures/microrect/shaders/MicrorectBuild.glsl) shares with the CPU twin: the claim codes
// (lightspace/Microrects.h MicrorectClaims) as CLAIMED_B, CLAIMED_D, CLAIMED_E.
std::vector<ShaderConstant> microrectBuildShaderConstants();
// The build shader's preamble for pass 1 or 2: MICRORECT_BUILD_PASS and the constants above.
ShaderDefines microrectBuildDefines(int pass);

// What the build leaves in the frame.
struct MicrorectData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> extentTexture; // RGBA16UI N x N atlas of levels 1..L
  vtkSmartPointer<vtkTextureObject> depthTexture;  // R32F N x N atlas of levels 1..L
  vtkSmartPointer<vtkTextureObject> claimTexture;  // R8UI ceil(N / 2)^2 build scratch (pass 1's claims)
  int mapSize = 0;
};

} // namespace sl
