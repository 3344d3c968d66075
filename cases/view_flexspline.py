# Opens a strainwave FEM result in ParaView, warps it by the displacement and colours it by hoop stress.
# Run:  pvpython cases/view_flexspline.py out/seed_190_192 [scale] [screenshot.png]
#   (or in the ParaView GUI: View > Python Shell > Run Script, after editing RESULT_DIR below)
# The displacement of a flexspline is a fraction of a millimetre on a part of ~40 mm, so the warp is exaggerated
# (default scale 20). Load case: the first dataset of flexspline.pvd (the wave generator alone when there is one).
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, OpenDataFile, Render,
                             ResetCamera, SaveScreenshot, Show, WarpByVector)

RESULT_DIR = sys.argv[1] if len(sys.argv) > 1 else "out/seed_190_192"
SCALE = float(sys.argv[2]) if len(sys.argv) > 2 else 20.0
SCREENSHOT = sys.argv[3] if len(sys.argv) > 3 else None

pvd = os.path.join(RESULT_DIR, "flexspline.pvd")
if not os.path.exists(pvd):
    sys.exit(f"{pvd}: not found; run `strainwave fem CASE.toml` first")
result = OpenDataFile(pvd)
warped = WarpByVector(Input=result)
warped.Vectors = ["POINTS", "displacement"]
warped.ScaleFactor = SCALE
view = GetActiveViewOrCreate("RenderView")
display = Show(warped, view)
ColorBy(display, ("POINTS", "stress_hoop"))
lut = GetColorTransferFunction("stress_hoop")
lut.ApplyPreset("Cool to Warm", True)
display.SetScalarBarVisibility(view, True)
ResetCamera()
Render()
if SCREENSHOT:
    SaveScreenshot(SCREENSHOT, view, ImageResolution=[1600, 1000])
