# `vtk`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 120
  DESCRIPTOR vtkTechnique VtkTechnique.h
  SOURCES VtkTechnique.cpp vtkSLVtkShadowMapPass.cxx
  SHADERS shaders/VtkVisibilityRatio.glsl)
