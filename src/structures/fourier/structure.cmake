# `fourier_basis`: the basis images of convolution shadow maps (convsm). Built after the shadow map.
sl_structure(
  ORDER 83
  STRUCTURE fourierBasisStructure FourierBasisStructure.h
  SOURCES FourierBasisStructure.cpp vtkSLFourierBasisPass.cxx
  SHADERS shaders/FourierBasis.glsl shaders/FourierTerms.glsl shaders/FourierBasisSparseBlur.glsl)
