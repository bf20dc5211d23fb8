"""Run by ParaView's pvbatch (check.py starts it as `xvfb-run -a pvbatch
pv_script.py DUMP_XMF PNG JSON`): open the time series DUMP_XMF with the
reader ParaView picks for it, list its time steps and, at the last one, the
point and cell arrays (name, components, range) and the point and cell
counts; render the cell field 'pressure' to PNG; write everything to JSON
for check.py to compare against the HDF5 dumps."""

import json
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetDisplayProperties,
                             OpenDataFile, Render, ResetCamera, SaveScreenshot, Show)

xmf, png, out = sys.argv[1:4]
reader = OpenDataFile(xmf)
reader.UpdatePipelineInformation()
times = [float(t) for t in reader.TimestepValues]
reader.UpdatePipeline(times[-1])
info = reader.GetDataInformation()
result = {
    "reader": reader.GetXMLName(),
    "times": times,
    "points": info.GetNumberOfPoints(),
    "cells": info.GetNumberOfCells(),
    "point_arrays": {},
    "cell_arrays": {},
}
for kind, arrays in (("point_arrays", reader.PointData), ("cell_arrays", reader.CellData)):
    for name in arrays.keys():
        a = arrays[name]
        result[kind][name] = {"components": a.GetNumberOfComponents(),
                              "range": list(a.GetRange(-1 if a.GetNumberOfComponents() > 1 else 0))}
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [480, 360]
view.ViewTime = times[-1]
Show(reader, view)
ColorBy(GetDisplayProperties(reader, view), ("CELLS", "pressure"))
GetDisplayProperties(reader, view).RescaleTransferFunctionToDataRange(True, False)
view.CameraPosition = [2.5, -2.0, 1.8]
view.CameraFocalPoint = [0.5, 0.5, 0.4]
view.CameraViewUp = [0.0, 0.0, 1.0]
ResetCamera(view)
Render(view)
SaveScreenshot(png, view, ImageResolution=[480, 360])
with open(out, "w") as f:
    json.dump(result, f, indent=1)
