set(SL_GL_SOURCES
  src/gl/EglContext.cpp
  src/gl/EglDeviceSelection.cpp
  src/gl/vtkSLEglRenderWindow.cxx
  src/gl/ShaderLibrary.cpp
  src/gl/GlResources.cpp
  src/gl/ComputeProgram.cpp
  src/gl/BandedPrefixSums.cpp)
