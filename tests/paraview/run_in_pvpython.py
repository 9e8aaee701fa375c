# Runs a script under pvpython whose paraview modules come from `root` (an unpacked python3-paraview package) ahead of
# any other VTK Python modules: Debian 12's python3-paraview cannot be installed beside libvtk9-dev (both ship
# vtkmodules), so scripts/bootstrap.sh unpacks it into the build directory, and pvpython there would otherwise import
# the system's VTK 9.1 modules first.
#   pvpython run_in_pvpython.py ROOT SCRIPT [ARGS...]
import runpy
import sys

root = sys.argv[1]
script = sys.argv[2]
own = root.rstrip("/") + "/usr/lib/python3/dist-packages"
sys.path = [own] + [entry for entry in sys.path if "dist-packages" not in entry or entry.startswith(root)]
sys.argv = [script] + sys.argv[3:]
runpy.run_path(script, run_name="__main__")
