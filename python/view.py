#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The standard views of a Sabo run folder, rendered to PNG, and an animation.

    python3 python/view.py RUN_DIR [--size 1280x720] [--every N] [--no-animation]

Writes RUN_DIR/views/: side.png (looking across the channel), oblique.png (from upstream, above), barrier.png
(looking down the channel at the barrier's face) at the last frame, and animation.gif (the oblique view over
the frames; every N-th frame). What is drawn, in world coordinates (the run's files are in the channel frame,
X down the slope: rotated here by the slope so that gravity points down):

- the grains (particles.pvd) as spheres coloured by speed [m/s];
- the barrier's spheres (barrier_spheres.pvd) coloured by the contact force on each [kN]; the barrier's
  boxes or mesh (geometry.vtp) in grey;
- the channel's walls (geometry.vtp), translucent;
- the fluid (fluid.pvd, debris and dam-break runs): its free surface, where the fill fraction is 0.5.

Needs Debian's python3-vtk9 (and Pillow, which python3-matplotlib brings, for the animation). Rendering needs a
display: without one the script starts itself again under `xvfb-run` (Debian's xvfb) when it is installed.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--size", default="1280x720", help="image size, WIDTHxHEIGHT pixels")
    parser.add_argument("--every", type=int, default=1, help="animate every N-th frame")
    parser.add_argument("--no-animation", action="store_true")
    args = parser.parse_args()
    if not os.environ.get("DISPLAY") and not os.environ.get("SABO_VIEW_UNDER_XVFB"):
        if shutil.which("xvfb-run"):  # a virtual display for the renderer
            env = dict(os.environ, SABO_VIEW_UNDER_XVFB="1")
            sys.exit(subprocess.call(["xvfb-run", "-a", sys.executable, *sys.argv], env=env))
        sys.exit("view.py: no display to render on: install xvfb (apt-get install xvfb) or set DISPLAY")
    try:
        import vtk  # noqa: F401
    except ImportError:
        sys.exit("view.py: needs python3-vtk9 (apt-get install python3-vtk9)")
    width, height = (int(v) for v in args.size.lower().split("x"))
    Views(args.run_dir, width, height).render_all(max(1, args.every), not args.no_animation)


def read_pvd(path):
    """(time, absolute file) of each data set of a .pvd series, in time order; [] without the file."""
    if not os.path.exists(path):
        return []
    root = ET.parse(path).getroot()
    folder = os.path.dirname(path)
    return sorted((float(d.get("timestep")), os.path.join(folder, d.get("file"))) for d in root.iter("DataSet"))


class Views:
    def __init__(self, run_dir, width, height):
        import vtk
        self.vtk = vtk
        self.dir = run_dir
        self.width, self.height = width, height
        with open(os.path.join(run_dir, "summary.json")) as f:
            self.summary = json.load(f)
        self.grains = read_pvd(os.path.join(run_dir, "particles.pvd"))
        self.barrier = read_pvd(os.path.join(run_dir, "barrier_spheres.pvd"))
        self.fluid = read_pvd(os.path.join(run_dir, "fluid.pvd"))
        # channel frame -> world: a rotation about Y by the slope takes X (down the slope) to
        # (cos θ, 0, -sin θ) and the bed's normal Z to (sin θ, 0, cos θ); gravity then points down
        self.world = vtk.vtkTransform()
        self.world.RotateY(float(self.summary.get("slope_deg") or 0.0))
        self.out = os.path.join(run_dir, "views")
        os.makedirs(self.out, exist_ok=True)
        self.max_speed = self._largest_speed()
        self.max_force_kN = self._largest_barrier_force()

    # --- data

    def _read(self, path):
        vtk = self.vtk
        reader = vtk.vtkXMLImageDataReader() if path.endswith(".vti") else vtk.vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        return reader.GetOutput()

    def _magnitudes(self, data, name, scale=1.0):
        """Adds |name| × scale as the point array name + '_magnitude'; returns its largest value."""
        vtk = self.vtk
        vectors = data.GetPointData().GetArray(name)
        out = vtk.vtkDoubleArray()
        out.SetName(name + "_magnitude")
        largest = 0.0
        if vectors is not None:
            for i in range(vectors.GetNumberOfTuples()):
                v = vectors.GetTuple3(i)
                m = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * scale
                out.InsertNextValue(m)
                largest = max(largest, m)
        data.GetPointData().AddArray(out)
        return largest

    def _largest_speed(self):
        return max([self._magnitudes(self._read(f), "velocity_m_s") for _, f in self.grains] + [1e-9])

    def _largest_barrier_force(self):
        return max([self._magnitudes(self._read(f), "force_N", 1e-3) for _, f in self.barrier] + [1e-9])

    def _frame_at(self, series, time):
        """The series' file at `time` (the last one not after it), None without one."""
        chosen = None
        for t, f in series:
            if t <= time + 1e-12:
                chosen = f
        return chosen

    # --- actors

    def _in_world(self, port):
        vtk = self.vtk
        moved = vtk.vtkTransformPolyDataFilter()
        moved.SetTransform(self.world)
        moved.SetInputConnection(port)
        return moved

    def _spheres(self, path, vector, scale, largest, colours, title):
        vtk = self.vtk
        data = self._read(path)
        self._magnitudes(data, vector, scale)
        data.GetPointData().SetActiveScalars("radius_m")
        ball = vtk.vtkSphereSource()
        ball.SetRadius(1.0)
        ball.SetThetaResolution(12)
        ball.SetPhiResolution(8)
        glyphs = vtk.vtkGlyph3D()
        glyphs.SetInputData(data)
        glyphs.SetSourceConnection(ball.GetOutputPort())
        glyphs.SetScaleModeToScaleByScalar()
        glyphs.SetColorModeToColorByScalar()
        glyphs.SetScaleFactor(1.0)
        glyphs.SetInputArrayToProcess(0, 0, 0, 0, "radius_m")       # size: the radius
        glyphs.SetInputArrayToProcess(3, 0, 0, 0, vector + "_magnitude")  # colour
        glyphs.OrientOff()
        moved = self._in_world(glyphs.GetOutputPort())
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputConnection(moved.GetOutputPort())
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray(vector + "_magnitude")
        mapper.SetScalarRange(0.0, largest)
        lut = vtk.vtkLookupTable()
        lut.SetHueRange(*colours)
        lut.Build()
        mapper.SetLookupTable(lut)
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        bar = vtk.vtkScalarBarActor()
        bar.SetLookupTable(lut)
        bar.SetTitle(title)
        bar.SetNumberOfLabels(5)
        bar.SetWidth(0.08)
        bar.SetHeight(0.4)
        bar.UnconstrainedFontSizeOn()
        for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
            text.SetColor(0.1, 0.1, 0.1)
            text.ItalicOff()
            text.ShadowOff()
            text.SetFontSize(max(10, self.height // 45))
        return actor, bar

    def _geometry(self):
        """The walls (translucent) and the barrier's boxes or mesh (grey) of geometry.vtp."""
        vtk = self.vtk
        path = os.path.join(self.dir, "geometry.vtp")
        if not os.path.exists(path):
            return []
        data = self._read(path)
        actors = []
        for barrier, colour, opacity in ((0, (0.75, 0.72, 0.65), 0.18), (1, (0.55, 0.55, 0.58), 1.0)):
            pick = vtk.vtkThreshold()
            pick.SetInputData(data)
            pick.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS, "barrier")
            pick.SetLowerThreshold(barrier - 0.5)
            pick.SetUpperThreshold(barrier + 0.5)
            surface = vtk.vtkGeometryFilter()
            surface.SetInputConnection(pick.GetOutputPort())
            actors.append(self._plain_surface(surface.GetOutputPort(), colour, opacity))
        return actors

    def _free_surface(self, path):
        """The fluid's free surface: where the fill fraction (cell data) is 0.5."""
        vtk = self.vtk
        image = self._read(path)
        image.GetCellData().SetActiveScalars("fill_fraction")
        to_points = vtk.vtkCellDataToPointData()
        to_points.SetInputData(image)
        contour = vtk.vtkContourFilter()
        contour.SetInputConnection(to_points.GetOutputPort())
        contour.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "fill_fraction")
        contour.SetValue(0, 0.5)
        return self._plain_surface(contour.GetOutputPort(), (0.35, 0.55, 0.85), 0.55)

    def _plain_surface(self, port, colour, opacity):
        """A surface of one colour, in world coordinates."""
        vtk = self.vtk
        moved = self._in_world(port)  # (held while connected: the pipeline then keeps it)
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputConnection(moved.GetOutputPort())
        mapper.ScalarVisibilityOff()
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*colour)
        actor.GetProperty().SetOpacity(opacity)
        return actor

    # --- rendering

    def _scene(self, time):
        vtk = self.vtk
        renderer = vtk.vtkRenderer()
        renderer.SetBackground(1.0, 1.0, 1.0)
        for actor in self._geometry():
            renderer.AddActor(actor)
        # the grains by speed, the barrier's spheres by force, each with its colour bar
        for series, vector, scale, largest, hues, title, bar_at in (
                (self.grains, "velocity_m_s", 1.0, self.max_speed, (0.667, 0.0), "grain speed [m/s]", 0.52),
                (self.barrier, "force_N", 1e-3, self.max_force_kN, (0.15, 0.0), "barrier force [kN]", 0.06)):
            frame = self._frame_at(series, time)
            if frame:
                actor, bar = self._spheres(frame, vector, scale, largest, hues, title)
                renderer.AddActor(actor)
                bar.SetPosition(0.90, bar_at)
                renderer.AddActor2D(bar)
        fluid = self._frame_at(self.fluid, time)
        if fluid:
            renderer.AddActor(self._free_surface(fluid))
        label = vtk.vtkTextActor()
        label.SetInput(f"{self.summary.get('case', '')}   t = {time:.2f} s")
        label.GetTextProperty().SetColor(0.1, 0.1, 0.1)
        label.GetTextProperty().SetFontSize(max(12, self.height // 40))
        label.SetPosition(10, 10)
        renderer.AddActor2D(label)
        return renderer

    def _camera(self, renderer, view):
        """Cameras in world coordinates (x down the valley, z up): the side and oblique views look at the
        barrier's reach (the whole scene without a barrier), the barrier view at its face from upstream."""
        renderer.ResetCamera()
        b = renderer.ComputeVisiblePropBounds()
        size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
        theta = math.radians(float(self.summary.get("slope_deg") or 0.0))
        face_x = self.summary.get("barrier_face_x_m")
        if face_x is not None:  # the barrier's face at mid-height, in world coordinates
            height = float(self.summary.get("barrier_height_m") or 1.0)
            x, z = float(face_x), 0.5 * height
            centre = [x * math.cos(theta) + z * math.sin(theta), centre[1], -x * math.sin(theta) + z * math.cos(theta)]
            size = max(6.0 * height, 0.5 * size)
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(*centre)
        offset = {"side": (0.0, -1.6, 0.1), "oblique": (-0.9, -1.0, 0.7), "barrier": (-1.1, 0.0, 0.45)}[view]
        camera.SetPosition(*(c + o * size for c, o in zip(centre, offset)))
        camera.SetViewUp(0.0, 0.0, 1.0)
        camera.SetViewAngle(30.0)
        renderer.ResetCameraClippingRange()

    def _render(self, time, view, path):
        vtk = self.vtk
        renderer = self._scene(time)
        self._camera(renderer, view)
        window = vtk.vtkRenderWindow()
        window.SetOffScreenRendering(1)
        window.AddRenderer(renderer)
        window.SetSize(self.width, self.height)
        window.Render()
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(path)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        window.Finalize()

    def render_all(self, every, animate):
        times = [t for t, _ in self.grains] or [t for t, _ in self.fluid]
        if not times:
            sys.exit(f"view.py: {self.dir} has no frames (particles.pvd or fluid.pvd)")
        last = times[-1]
        written = []
        for view in ("side", "oblique", "barrier"):
            path = os.path.join(self.out, f"{view}.png")
            self._render(last, view, path)
            written.append(path)
        if animate:
            for old in os.listdir(self.out):  # a previous rendering's frames
                if old.startswith("frame_") and old.endswith(".png"):
                    os.remove(os.path.join(self.out, old))
            frames = []
            for k, t in enumerate(times[::every]):
                path = os.path.join(self.out, f"frame_{k:05d}.png")
                self._render(t, "oblique", path)
                frames.append(path)
            gif = os.path.join(self.out, "animation.gif")
            try:
                from PIL import Image
                images = [Image.open(f).convert("P", palette=Image.ADAPTIVE) for f in frames]
                images[0].save(gif, save_all=True, append_images=images[1:], duration=400, loop=0)
                written.append(gif)
            except ImportError:
                print("view.py: no Pillow (python3-pil): the animation's frames are left as PNGs")
            written += frames
        print(f"view.py: wrote {len(written)} files in {self.out} (t = {times[0]:g} ... {last:g} s, "
              f"{len(times)} frames)")


if __name__ == "__main__":
    main()
