set(SL_TECHNIQUES_SOURCES
  src/techniques/vtkSLTechniquePass.cxx
  src/techniques/Registry.cpp
  src/techniques/ShadowMapParameters.cpp
  src/techniques/ShadowMapReference.cpp
  src/techniques/ProbeSupport.cpp
  src/techniques/ApproximationRules.cpp
  src/techniques/SamplingPatterns.cpp
  src/techniques/SoftShadowSupport.cpp
  src/techniques/MomentReference.cpp
  src/techniques/MomentTechniquePass.cxx
  src/techniques/hard/HardTechnique.cpp
  src/techniques/hard/vtkSLHardShadowPass.cxx
  src/techniques/pcf/PcfTechnique.cpp
  src/techniques/pcf/vtkSLPcfPass.cxx
  src/techniques/pcss/PcssTechnique.cpp
  src/techniques/pcss/vtkSLPcssPass.cxx
  src/techniques/vsm/VsmTechnique.cpp
  src/techniques/esm/EsmTechnique.cpp
  src/techniques/savsm/SavsmTechnique.cpp
  src/techniques/savsm/vtkSLSavsmPass.cxx
  src/techniques/vssm/VssmTechnique.cpp
  src/techniques/vssm/vtkSLVssmPass.cxx
  src/techniques/backprojection/ContourBackprojection.cpp
  src/techniques/backprojection/ContourReceiver.cpp
  src/techniques/gbp06/Gbp06Technique.cpp
  src/techniques/gbp06/vtkSLGbp06Pass.cxx
  src/techniques/gbp07/Gbp07Technique.cpp
  src/techniques/gbp07/vtkSLGbp07Pass.cxx
  src/techniques/yfgl09/Yfgl09Technique.cpp
  src/techniques/yfgl09/vtkSLYfgl09Pass.cxx
  src/techniques/ss08/Ss08Technique.cpp
  src/techniques/ss08/vtkSLSs08Pass.cxx
  src/techniques/vtk/VtkTechnique.cpp
  src/techniques/vtk/vtkSLVtkShadowMapPass.cxx
  src/techniques/referencesm/ReferenceSmTechnique.cpp
  src/techniques/referencesm/vtkSLReferenceShadowMapPass.cxx
  src/techniques/shadowvolume/ShadowVolumeGeometry.cpp src/techniques/shadowvolume/ShadowVolumeReference.cpp src/techniques/shadowvolume/SilhouetteExport.cpp src/techniques/shadowvolume/ShadowVolumeTechnique.cpp src/techniques/shadowvolume/vtkSLShadowVolumePass.cxx
  src/techniques/dcs/DcsGeometry.cpp src/techniques/dcs/DcsReference.cpp src/techniques/dcs/DcsWedgeExport.cpp src/techniques/dcs/DcsTechnique.cpp src/techniques/dcs/WedgeDrawer.cpp src/techniques/dcs/vtkSLDcsPass.cxx
  src/techniques/stsv/StsvGeometry.cpp src/techniques/stsv/StsvDrawer.cpp
  src/techniques/penumbrawedge/PenumbraWedgeGeometry.cpp src/techniques/penumbrawedge/PenumbraWedgeTechnique.cpp src/techniques/penumbrawedge/vtkSLPenumbraWedgePass.cxx)
