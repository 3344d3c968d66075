# Renders strainwave results with ParaView: a FEM load case warped by its displacement and coloured by a field, or the
# tooth profiles of the backlash stage. Run with pvbatch or pvpython (scripts/pvbatch.sh sets them up headless):
#   scripts/pvbatch.sh cases/view_flexspline.py out/seed_190_192 --case generator --field stress_hoop --png view.png
#   scripts/pvbatch.sh cases/view_flexspline.py out/seed_190_192/profiles.vtp --png profiles.png
# Options: --case NAME (a dataset of flexspline.pvd: generator, torque, generator_torque; default the first),
#          --field NAME (a point field of the .vtu; stress fields are shown in MPa), --scale S (warp factor, default
#          20: the displacement is a fraction of a millimetre on a part of ~40 mm), --png FILE, --probe FILE.json (the
#          warped bounds and the field's range as ParaView computed them, for checks). Profiles are shown zoomed on
#          the mesh zone at the major axis (+x, teeth pointing up), where the teeth are visible; --whole shows the gear.
# In the ParaView GUI: open flexspline.pvd, apply Warp By Vector (displacement is the active vector), colour by a field.
import argparse
import json
import os
import sys
import xml.etree.ElementTree as ET

from paraview.simple import (Calculator, ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar,
                             OpenDataFile, Render, ResetCamera, SaveScreenshot, Show, WarpByVector)

parser = argparse.ArgumentParser(description="render a strainwave result with ParaView")
parser.add_argument("result", help="output folder of `strainwave fem`/`run`, or a profiles.vtp")
parser.add_argument("--case", default=None, help="load case (dataset name in flexspline.pvd)")
parser.add_argument("--field", default="stress_hoop", help="point field to colour by")
parser.add_argument("--scale", type=float, default=20.0, help="warp scale factor")
parser.add_argument("--png", default=None, help="screenshot file")
parser.add_argument("--probe", default=None, help="write bounds and field range as JSON")
parser.add_argument("--whole", action="store_true", help="profiles: the whole gear instead of the major axis's mesh zone")
args = parser.parse_args()

view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
probe = {}


def place_bar(bar, horizontal=False):
    """The colour bar in the picture's right margin (the part is drawn left of it), or along its bottom edge (the
    profiles' legend, under the teeth); dark text on white."""
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Horizontal" if horizontal else "Vertical"
    bar.Position = [0.15, 0.06] if horizontal else [0.84, 0.2]
    bar.ScalarBarLength = 0.7 if horizontal else 0.6
    bar.ScalarBarThickness = 12
    bar.TitleFontSize = 16
    bar.LabelFontSize = 14
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.RangeLabelFormat = "%-#.3g"

if args.result.endswith(".vtp"):
    if not os.path.exists(args.result):
        sys.exit(f"{args.result}: not found; run `strainwave backlash CASE.toml` first")
    profiles = OpenDataFile(args.result)
    display = Show(profiles, view)
    ColorBy(display, ("CELLS", "part"))
    # Three parts, three colours that read on white, and lines thick enough to see the flanks' gaps.
    lut = GetColorTransferFunction("part")
    lut.InterpretValuesAsCategories = 1
    lut.Annotations = ["0", "flexspline", "1", "flexspline turned by phi0", "2", "circular spline"]
    lut.IndexedColors = [0.12, 0.35, 0.75, 0.90, 0.45, 0.05, 0.15, 0.15, 0.15]
    display.LineWidth = 3.0
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = ""
    bar.ComponentTitle = ""
    place_bar(bar, horizontal=True)
    profiles.UpdatePipeline()
    probe["bounds"] = list(profiles.GetDataInformation().GetBounds())
    probe["field"] = "part"
    probe["range"] = list(profiles.CellData["part"].GetRange())
else:
    pvd = os.path.join(args.result, "flexspline.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"{pvd}: not found; run `strainwave fem CASE.toml` first")
    datasets = {d.get("name"): d.get("file") for d in ET.parse(pvd).getroot().iter("DataSet")}
    name = args.case or next(iter(datasets))
    if name not in datasets:
        sys.exit(f"{pvd}: no load case '{name}' (has: {', '.join(datasets)})")
    result = OpenDataFile(os.path.join(args.result, datasets[name]))
    result.UpdatePipeline()
    if args.field not in result.PointData.keys():
        sys.exit(f"{datasets[name]}: no point field '{args.field}' (has: {', '.join(result.PointData.keys())})")
    warped = WarpByVector(Input=result)
    warped.Vectors = ["POINTS", "displacement"]
    warped.ScaleFactor = args.scale
    shown, field = warped, args.field
    if args.field.startswith("stress") or args.field == "von_mises":
        field = args.field + "_MPa"
        shown = Calculator(Input=warped, ResultArrayName=field, Function=f"{args.field}/1e6")
    shown.UpdatePipeline()
    display = Show(shown, view)
    ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Cool to Warm", True)
    display.SetScalarBarVisibility(view, True)
    place_bar(GetScalarBar(lut, view))
    probe["case"] = name
    probe["bounds"] = list(shown.GetDataInformation().GetBounds())
    probe["field"] = field
    probe["range"] = list(shown.PointData[field].GetRange())
ResetCamera()
if args.result.endswith(".vtp") and not args.whole:
    # The teeth are a hairline on the whole gear: look at the major axis (+x) over about ±3.5°, teeth pointing up.
    r = probe["bounds"][1]
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [0.985 * r, 0.0, 0.0]
    view.CameraPosition = [0.985 * r, 0.0, 10.0 * r]
    view.CameraViewUp = [1.0, 0.0, 0.0]
    view.CameraParallelScale = 0.06 * r / 1.5  # half the height of a 3:2 picture showing ±0.06 r across
Render()
if args.png:
    SaveScreenshot(args.png, view, ImageResolution=[1200, 800], FontScaling="Do not scale fonts")
if args.probe:
    with open(args.probe, "w") as f:
        json.dump(probe, f)
