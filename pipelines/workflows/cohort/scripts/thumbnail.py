#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A thumbnail of a case's mesh, flat-shaded from a fixed oblique view, rendered offscreen with VTK
(Debian's python3-vtk9). A failed case gets a grey card with the error. Debian's VTK draws through X even
offscreen: without a display the script runs itself again under xvfb-run."""
import argparse
import json
import os
import subprocess
import sys
import textwrap


def render(summary, png, size):
    from vtkmodules.vtkIOGeometry import vtkSTLReader, vtkOBJReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                             vtkTextActor, vtkWindowToImageFilter)
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the render window implementation)
    import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text)

    renderer = vtkRenderer()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    if summary.get("status") == "ok":
        mesh = summary["mesh"]
        ext = os.path.splitext(mesh)[1].lower()
        reader = {".stl": vtkSTLReader, ".ply": vtkPLYReader, ".vtp": vtkXMLPolyDataReader, ".obj": vtkOBJReader}[ext]()
        reader.SetFileName(mesh)
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(reader.GetOutputPort())
        mapper.ScalarVisibilityOff()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(0.93, 0.87, 0.72)  # bone
        actor.GetProperty().SetInterpolationToFlat()
        renderer.AddActor(actor)
        renderer.SetBackground(0.16, 0.18, 0.22)
        camera = renderer.GetActiveCamera()
        camera.SetPosition(1.0, -1.6, 0.9)
        camera.SetFocalPoint(0.0, 0.0, 0.0)
        camera.SetViewUp(0.0, 0.0, 1.0)
        renderer.ResetCamera()
    else:
        renderer.SetBackground(0.55, 0.55, 0.55)
        text = vtkTextActor()
        message = "FAILED\n" + "\n".join(textwrap.wrap(summary.get("error", ""), 28)[:6])
        text.SetInput(message)
        text.GetTextProperty().SetFontSize(max(10, size // 18))
        text.GetTextProperty().SetColor(1.0, 1.0, 1.0)
        text.SetPosition(8, 8)
        renderer.AddActor2D(text)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    tmp = png + ".tmp.png"
    writer.SetFileName(tmp)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    os.replace(tmp, png)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("summary")
    p.add_argument("png")
    p.add_argument("--size", type=int, default=240)
    a = p.parse_args()
    if not os.environ.get("DISPLAY") and not os.environ.get("CONTOURMESH_UNDER_XVFB"):
        env = dict(os.environ, CONTOURMESH_UNDER_XVFB="1")
        sys.exit(subprocess.run(["xvfb-run", "-a", sys.executable, *sys.argv], env=env).returncode)
    with open(a.summary) as f:
        summary = json.load(f)
    render(summary, a.png, a.size)


if __name__ == "__main__":
    main()
