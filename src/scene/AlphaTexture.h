// Alpha (perforation) textures: from a PNG, or one of two procedural patterns.
//
// All produce a 1-component ImageF with values in [0,1], row 0 = v near 0 (the bottom row of the picture,
// as in OpenGL and vtkImageData). Texel (x, y) covers u in [x, x+1)/width, v in [y, y+1)/height; the
// procedural patterns are evaluated at texel centres and tile seamlessly under repeat wrap. Renderers treat
// alpha < 0.5 as a hole (see AlphaTexture in Scene.h).
//
// Procedural patterns (kProceduralAlphaSize x kProceduralAlphaSize):
//  - "fence": a chain-link-like diamond grid. With u' = u + v and v' = u - v (the grid rotated by 45
//    degrees), a texel is a hole (alpha 0) where both fract(8u') and fract(8v') lie in the open interval
//    (0.15, 0.85), and a wire (alpha 1) elsewhere. About 49% of the texture is holes (0.7^2).
//  - "leaves": kLeavesEllipseCount opaque ellipses (alpha 1) of random position, size and orientation on
//    a transparent background (alpha 0), from a fixed-seed splitmix64 sequence, so the pattern is the same
//    on every platform and run. Ellipses wrap around the texture edges (it tiles); they overlap, and their
//    sizes are chosen so that about half of the texture is opaque.
#pragma once

#include "core/Image.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <string>

namespace sl
{

constexpr int kProceduralAlphaSize = 256;
constexpr int kLeavesEllipseCount = 60;

// Alpha of a PNG (decoded by libpng, readPngImage in io/ImageIO.h): the alpha channel when the PNG has one
// (gray+alpha, RGBA, or a tRNS chunk, as palette images often have), otherwise its luminance (Rec. 709
// weights for RGB and palette colours). Every colour type and bit depth is accepted; samples are normalised
// to [0,1]. At most kMaxImageSide (16384) texels per side. Throws InputError "cannot read '<file>' (<why>)"
// for a missing, non-PNG, too large or corrupt file (libpng's reason, e.g. "IDAT: invalid block type").
ImageF readAlphaPng(const std::filesystem::path& file);

ImageF makeFenceAlpha(int size = kProceduralAlphaSize);
ImageF makeLeavesAlpha(int size = kProceduralAlphaSize);

// True for the names the scene format reserves for procedural patterns ("fence", "leaves").
bool isProceduralAlphaName(const std::string& source);

// True where the mask `alpha` has a hole at texture coordinates `uv`: alpha < 0.5 at the nearest texel under
// repeat wrap (texel i covers [i, i+1)/size, coordinates wrap modulo 1), as isPerforated in
// shaders/common/AlphaMask.glsl decides. A coordinate too large to name a texel (non-finite) reads texel 0.
// For the CPU references that sample the mask themselves (Embree's occlusion filter, reference-sm's replay, the
// tests' ray caster).
bool alphaHoleAt(const ImageF& alpha, const glm::dvec2& uv);

// The alpha texture a scene's `alpha_texture` string names: a procedural pattern, or a PNG path resolved
// relative to `baseDir`. Throws InputError as readAlphaPng does.
AlphaTexture makeAlphaTexture(const std::string& source, const std::filesystem::path& baseDir);

} // namespace sl
