# SPDX-License-Identifier: GPL-3.0-or-later
# plates.py: a ParaView picture of a spheroplate pack written by packexport --vtk.
# usage: xvfb-run -a pvbatch share/plot/plates.py PLATES.vtp OUT.png
# (the camera is set for a box of about 1.1 um, packgen's 1000 plates at eta 0.5; each
# plate is coloured by the z component of its face normal)
import sys
from paraview.simple import *
r = XMLPolyDataReader(FileName=[sys.argv[1]])
r.UpdatePipeline()
info = r.GetDataInformation()
print("points", info.GetNumberOfPoints(), "cells", info.GetNumberOfCells())
v = GetActiveViewOrCreate("RenderView"); v.ViewSize = [900, 700]; v.Background = [1, 1, 1]
try:
    v.UseColorPaletteForBackground = 0
except Exception: pass
try:
    v.OrientationAxesVisibility = 0
except Exception: pass
d = Show(r, v); ColorBy(d, ("CELLS", "normal", "Z")); d.LookupTable = GetColorTransferFunction("normal"); d.LookupTable.ApplyPreset("Cool to Warm", True)
v.CameraPosition = [3.6e-6, -2.2e-6, 2.8e-6]
Render(v); SaveScreenshot(sys.argv[2], v, ImageResolution=[900, 700])
