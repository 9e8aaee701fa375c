#include "passes/PassUtilities.h"

#include <vtkShaderProgram.h>
#include <vtkTextureObject.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace sl
{

void setMatrix(vtkShaderProgram* program, const char* name, const glm::dmat4& matrix)
{
  glm::mat4 single(matrix);
  program->SetUniformMatrix4x4(name, glm::value_ptr(single)); // column-major, as GLSL expects
}

void setVector(vtkShaderProgram* program, const char* name, const glm::dvec3& vector)
{
  const float values[3] = { static_cast<float>(vector.x), static_cast<float>(vector.y), static_cast<float>(vector.z) };
  program->SetUniform3f(name, values);
}

void setFloatIfUsed(vtkShaderProgram* program, const char* name, double value)
{
  if (program->IsUniformUsed(name))
  {
    program->SetUniformf(name, static_cast<float>(value));
  }
}

void setIntIfUsed(vtkShaderProgram* program, const char* name, int value)
{
  if (program->IsUniformUsed(name))
  {
    program->SetUniformi(name, value);
  }
}

int lightTypeCode(LightType type)
{
  switch (type)
  {
    case LightType::Area: return 0;
    case LightType::Point: return 1;
    case LightType::Directional: return 2;
    case LightType::Spot: return 3;
  }
  return 0;
}

ShaderDefines commonDefines()
{
  return { { "SL_LIGHT_AREA", std::to_string(lightTypeCode(LightType::Area)) },
    { "SL_LIGHT_POINT", std::to_string(lightTypeCode(LightType::Point)) },
    { "SL_LIGHT_DIRECTIONAL", std::to_string(lightTypeCode(LightType::Directional)) },
    { "SL_LIGHT_SPOT", std::to_string(lightTypeCode(LightType::Spot)) } };
}

void setCameraRayUniforms(vtkShaderProgram* program, const CameraView& camera)
{
  setVector(program, "cameraNearOrigin", camera.nearOrigin);
  setVector(program, "cameraNearStepX", camera.nearStepX);
  setVector(program, "cameraNearStepY", camera.nearStepY);
  setVector(program, "cameraRayOrigin", camera.rayOrigin);
  setVector(program, "cameraRayStepX", camera.rayStepX);
  setVector(program, "cameraRayStepY", camera.rayStepY);
}

void setLightUniforms(vtkShaderProgram* program, const Light& light)
{
  setIntIfUsed(program, "lightType", lightTypeCode(light.type));
  if (program->IsUniformUsed("lightCenterWs"))
  {
    setVector(program, "lightCenterWs", light.center);
  }
  if (program->IsUniformUsed("lightNormalWs"))
  {
    setVector(program, "lightNormalWs", light.normal);
  }
  if (program->IsUniformUsed("lightDirectionWs"))
  {
    setVector(program, "lightDirectionWs", light.direction);
  }
  setFloatIfUsed(program, "lightCosCone", std::cos(light.coneAngleDeg * 3.14159265358979323846 / 180.0));
}

vtkTextureObject* bindTexture(vtkShaderProgram* program, const char* samplerName, vtkTextureObject* texture)
{
  texture->Activate();
  program->SetUniformi(samplerName, texture->GetTextureUnit());
  return texture;
}

} // namespace sl
