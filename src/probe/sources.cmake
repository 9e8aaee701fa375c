# What a technique's probe recorded, presented (src/probe/Probe.h): probe.json, probe.vtm, probe.png.
set(SL_PROBE_SOURCES
  src/probe/Probe.cpp
  src/probe/ProbeDataSet.cxx
  src/probe/ProbeFigure.cxx
  src/probe/ProbeGeometry.cpp)
