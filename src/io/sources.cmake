set(SL_IO_SOURCES
  src/io/ImageIO.cpp
  src/io/OutputWriter.cpp)
