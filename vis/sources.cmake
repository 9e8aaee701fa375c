# Heat maps and their colour keys (see vis/HeatMap.h), the bench charts (vis/SpeedErrorChart.h, vis/StageChart.h, vis/SweepChart.h, vis/DepthProfileChart.h). Needs VTK RenderingFreeType (text) and IOImage (PNG).
set(SL_VIS_SOURCES
  vis/BufferHeatMap.cxx
  vis/Canvas.cxx
  vis/CanvasShapes.cxx
  vis/ColorKey.cxx
  vis/NumberText.cxx
  vis/ColorMap.cxx
  vis/HeatMap.cxx
  vis/Montage.cxx
  vis/ChartSupport.cxx
  vis/SpeedErrorChart.cxx
  vis/StageChart.cxx
  vis/vtkSLPointLabels.cxx
  vis/SweepChart.cxx
  vis/DepthProfileChart.cxx)
