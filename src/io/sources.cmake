set(SL_IO_SOURCES
  src/io/ImageIO.cpp
  src/io/OutputDirectory.cpp
  src/io/vtkSLOutputWindow.cxx)
