# Every GLSL file embedded into shadowlab, by path under shaders/ (listed explicitly, no glob).
set(SL_SHADER_FILES
  common/AlphaMask.glsl
  common/FullScreenVertex.glsl
  common/GBufferInputs.glsl
  common/LightModel.glsl
  common/PixelHash.glsl
  common/ShadowMapCommon.glsl
  common/ShadowReceiver.glsl
  common/TexelRatio.glsl
  gbuffer/GBufferVertex.glsl
  gbuffer/GBufferFragment.glsl
  lightspace/LightDepthVertex.glsl
  lightspace/LightDepthFragment.glsl
  hard/HardVisibility.glsl
  pcf/PcfVisibility.glsl
  shading/ShadingFragment.glsl
  vtk/VtkVisibilityRatio.glsl)
