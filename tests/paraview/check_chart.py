# A chart screenshot is not a blank view: at least 0.5 % of its pixels differ from its most common colour (the
# background), i.e. axes, labels and points were drawn. Run under pvpython (reads the PNG with VTK).
#   check_chart.py CHART_PNG
import collections
import sys

from vtkmodules.vtkIOImage import vtkPNGReader

reader = vtkPNGReader()
reader.SetFileName(sys.argv[1])
reader.Update()
image = reader.GetOutput()
width, height, _ = image.GetDimensions()
scalars = image.GetPointData().GetScalars()
colours = collections.Counter(scalars.GetTuple(i)[:3] for i in range(width * height))
background, count = colours.most_common(1)[0]
drawn = width * height - count
print("%s: %dx%d, %d pixels differ from the background %s" % (sys.argv[1], width, height, drawn, background))
if width == 0 or drawn < 0.005 * width * height:
    raise SystemExit("FAIL: the chart looks blank")
