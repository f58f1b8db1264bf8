#!/usr/bin/env python3
"""Times VTK's CPU ray caster on issue 6's three scenes, on this machine, for comparison with
`kdswap bench --targets` (the issue's VTK figures were measured on another machine).

What users would pick instead: vtkFixedPointVolumeRayCastMapper (Debian's python3-vtk9), 512x512,
shading on, linear interpolation, grey ramp colour, opacity 0 up to 10% of the range rising to 0.8,
the camera orbiting 1 degree per frame (kdswap's view: azimuth 30, elevation 15, +z up, 2.5
bounding-sphere radii away, 35 degree field of view), median of the frames. The volumes are
written by `kdswap export`, so both renderers see the same voxels.

Usage (needs an X display for VTK's window, e.g. under xvfb-run):
  apt-get install python3-vtk9 xvfb
  xvfb-run -a /usr/bin/python3 scripts/vtk_baseline.py [--kdswap build/app/kdswap] [--threads 2]
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import time

try:
    import numpy
    import vtk
    from vtk.util import numpy_support
except ImportError as e:
    sys.exit("vtk_baseline: needs VTK's Python module and numpy (apt-get install python3-vtk9): %s" % e)

# name, export arguments, sample distance in voxels; as issue 6 lists them.
SCENES = [
    ("turbulence 256^3 (quantised to 16 bits), step 1", ["--dataset", "turbulence:256", "--quantise", "16"], 1.0),
    ("phantom 256^3 uint8, step 1", ["--dataset", "phantom:256", "--quantise", "8"], 1.0),
    ("CT head headsq 64x64x93 (unit spacing), step 0.5",
     ["--volume", "../shared/data/headsq.nhdr", "--spacing", "1,1,1", "--quantise", "16"], 0.5),
]


def read_nrrd(path):
    """The attached raw NRRD files `kdswap export` writes, as VTK image data."""
    with open(path, "rb") as f:
        fields = {}
        f.readline()  # NRRD0004
        while True:
            line = f.readline().decode()
            if line.strip() == "":
                break
            if line.startswith("#"):
                continue
            key, _, value = line.partition(":")
            fields[key.strip()] = value.strip()
        dtype = {"uint8": numpy.uint8, "uint16": numpy.uint16, "float": numpy.float32}[fields["type"]]
        data = numpy.frombuffer(f.read(), dtype=dtype)
    sizes = [int(s) for s in fields["sizes"].split()]
    image = vtk.vtkImageData()
    image.SetDimensions(*sizes)
    image.SetSpacing(*[float(s) for s in fields["spacings"].split()])
    image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(data, deep=True))
    return image


def time_scene(image, step_voxels, frames, threads, png=None):
    lo, hi = image.GetScalarRange()
    colour = vtk.vtkColorTransferFunction()
    colour.AddRGBPoint(lo, 0, 0, 0)
    colour.AddRGBPoint(hi, 1, 1, 1)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(lo, 0)
    opacity.AddPoint(lo + 0.1 * (hi - lo), 0)
    opacity.AddPoint(hi, 0.8)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(colour)
    prop.SetScalarOpacity(opacity)
    prop.SetInterpolationTypeToLinear()
    prop.ShadeOn()
    prop.SetAmbient(0.3), prop.SetDiffuse(0.7), prop.SetSpecular(0.3), prop.SetSpecularPower(24)
    mapper = vtk.vtkFixedPointVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.SetNumberOfThreads(threads)
    mapper.SetAutoAdjustSampleDistances(0)
    mapper.SetSampleDistance(step_voxels * min(image.GetSpacing()))
    mapper.SetImageSampleDistance(1.0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer = vtk.vtkRenderer()
    renderer.AddVolume(volume)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.AddRenderer(renderer)
    window.SetSize(512, 512)
    # kdswap's orbit camera (core/camera/camera.cpp): front = -y, side = +x, up = +z.
    dims, spacing = image.GetDimensions(), image.GetSpacing()
    extent = [(d - 1) * s for d, s in zip(dims, spacing)]
    centre = [e / 2 for e in extent]
    radius = 0.5 * math.sqrt(sum(e * e for e in extent))
    camera = renderer.GetActiveCamera()
    camera.SetViewAngle(35)
    camera.SetViewUp(0, 0, 1)
    camera.SetFocalPoint(*centre)
    times = []
    for frame in range(frames + 1):  # frame 0 warms up, as kdswap bench
        az, el = math.radians(30 + frame), math.radians(15)
        to_eye = (math.cos(el) * math.sin(az), -math.cos(el) * math.cos(az), math.sin(el))
        camera.SetPosition(*[c + 2.5 * radius * t for c, t in zip(centre, to_eye)])
        renderer.ResetCameraClippingRange()
        start = time.perf_counter()
        window.Render()
        if frame > 0:
            times.append(time.perf_counter() - start)
    if png:  # the last frame, to compare its framing and look with kdswap's
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(png)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
    return statistics.median(times) * 1e3


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--kdswap", default="build/app/kdswap", help="kdswap binary, used to export the volumes")
    parser.add_argument("--data-dir", default="bench-out/vtk", help="where the exported volumes are kept")
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--pictures", action="store_true", help="also write each scene's last frame as PNG")
    args = parser.parse_args()
    os.makedirs(args.data_dir, exist_ok=True)
    medians = []
    for i, (name, export_args, step) in enumerate(SCENES):
        path = os.path.join(args.data_dir, "scene%d.nrrd" % i)
        if not os.path.exists(path):
            subprocess.run([args.kdswap, "export", *export_args, "--out", path], check=True, stdout=subprocess.DEVNULL)
        png = os.path.join(args.data_dir, "scene%d.png" % i) if args.pictures else None
        ms = time_scene(read_nrrd(path), step, args.frames, args.threads, png)
        print("VTK %-52s %8.1f ms  (median of %d frames, %d threads)" % (name, ms, args.frames, args.threads), flush=True)
        medians.append(ms)
    print("compare: kdswap bench --targets --vtk-ms %s" % ",".join("%.0f" % m for m in medians))


if __name__ == "__main__":
    main()
