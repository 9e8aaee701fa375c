// Helpers shared by the pass implementations (uniform upload in our conventions, light enums for GLSL).
#pragma once

#include "gl/ShaderLibrary.h"
#include "lightspace/CameraView.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

class vtkShaderProgram;
class vtkTextureObject;

namespace sl
{

struct FrameResources;

void setMatrix(vtkShaderProgram* program, const char* name, const glm::dmat4& matrix);
void setVector(vtkShaderProgram* program, const char* name, const glm::dvec3& vector);
// Sets a uniform only when the program uses it (optimised-away uniforms are not errors).
void setFloatIfUsed(vtkShaderProgram* program, const char* name, double value);
void setIntIfUsed(vtkShaderProgram* program, const char* name, int value);

// Defines every shader gets: SL_LIGHT_AREA, SL_LIGHT_POINT, ... (the LightType enumeration).
ShaderDefines commonDefines();
int lightTypeCode(LightType type);

// Light uniforms of common/LightModel.glsl.
void setLightUniforms(vtkShaderProgram* program, const Light& light);
// The camera ray uniforms of shaders/common/CameraRay.glsl.
void setCameraRayUniforms(vtkShaderProgram* program, const CameraView& camera);

// Activates `texture` on a free unit and points the sampler uniform at it. Returns the texture so the
// caller can Deactivate() it after drawing.
vtkTextureObject* bindTexture(vtkShaderProgram* program, const char* samplerName, vtkTextureObject* texture);

} // namespace sl
