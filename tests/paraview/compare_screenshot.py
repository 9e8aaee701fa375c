# Compares ParaView's screenshot of a buffer (open_in_paraview.py --screenshot, one pixel per buffer pixel) with the
# same buffer's heat map PNG (its values drawn 1:1 at the bottom-left, vis/HeatMap.h): the script must reproduce the
# heat map's colour map and range. Compared where the heat map's 3 x 3 neighbourhood has one colour (ParaView
# interpolates between pixel centres, so edges differ by design). Run under pvpython (it reads PNGs with VTK).
#   compare_screenshot.py HEATMAP_PNG SCREENSHOT_PNG WIDTH HEIGHT
import sys

from vtkmodules.vtkIOImage import vtkPNGReader


def read_rgb(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    scalars = image.GetPointData().GetScalars()
    components = scalars.GetNumberOfComponents()
    pixels = [scalars.GetTuple(i)[:3] for i in range(width * height)]
    if width == 0 or components < 3:
        raise SystemExit("compare_screenshot.py: %s is not an RGB PNG" % path)
    return width, height, pixels


heat_path, shot_path, width, height = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
heat_width, heat_height, heat = read_rgb(heat_path)
shot_width, shot_height, shot = read_rgb(shot_path)
if (shot_width, shot_height) != (width, height):
    raise SystemExit("FAIL %s: screenshot is %dx%d, expected %dx%d" % (shot_path, shot_width, shot_height, width, height))


def heat_at(x, y):  # row 0 = bottom in both (VTK's PNG reader flips)
    return heat[y * heat_width + x]


compared = 0
worst = 0.0
off = 0
for y in range(1, height - 1):
    for x in range(1, width - 1):
        colour = heat_at(x, y)
        if any(heat_at(x + dx, y + dy) != colour for dx in (-1, 0, 1) for dy in (-1, 0, 1)):
            continue
        got = shot[y * width + x]
        difference = max(abs(a - b) for a, b in zip(colour, got))
        worst = max(worst, difference)
        off += difference > 6
        compared += 1
print("%s: %d uniform pixels compared, %d differ by more than 6/255, largest difference %d/255"
      % (shot_path, compared, off, worst))
if compared < 0.3 * width * height:
    raise SystemExit("FAIL: only %d of %d pixels have a uniform neighbourhood" % (compared, width * height))
if off > 0.01 * compared:
    raise SystemExit("FAIL: %d of %d pixels differ from the heat map by more than 6/255" % (off, compared))
