# `penumbra-wedge`: what the build takes from this folder (cmake/Techniques.cmake reads every technique.cmake).
sl_technique(
  ORDER 160
  DESCRIPTOR penumbraWedgeTechnique PenumbraWedgeTechnique.h
  SOURCES PenumbraWedgeGeometry.cpp PenumbraWedgeTechnique.cpp vtkSLPenumbraWedgePass.cxx
  SHADERS shaders/PenumbraWedgeArea.glsl shaders/PenumbraWedgeResolve.glsl
  GPU_TESTS tests/PenumbraWedgeTest.cpp)
