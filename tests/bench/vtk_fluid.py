"""Renders one benchmark frame with VTK's screen-space fluid mapper, the peer Spindrift is measured against.

    xvfb-run -a -s "-screen 0 1280x720x24" /usr/bin/python3 tests/bench/vtk_fluid.py \
        scene.json particles.ply out.npz [--repeats 5] [--filter narrow_range|bilateral]

Same camera (scene.json's world_from_camera and vertical field of view), same particles and radius (the PLY
that tests/bench/export_particles.cpp writes), the same Cycles background image as the textured background
that the mapper refracts, IOR 1.33 and the same absorption colour. VTK 9.1's vtkOpenGLFluidMapper draws
nothing unless the window has no multisampling and the mapper sits in a vtkVolume (environment notes).

Writes out.npz: `composite` (H x W x 3, linear RGB), `frame_ms` (every timed render, after one warm-up
render that compiles the shaders) and `first_frame_ms`, plus the GL renderer string.
"""

import argparse
import json
import os
import time

import numpy as np
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkRenderingCore import (vtkRenderer, vtkRenderWindow, vtkTexture, vtkVolume,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLFluidMapper
from vtkmodules.vtkCommonDataModel import vtkImageData

import metrics


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene")
    parser.add_argument("particles")
    parser.add_argument("output")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--filter", choices=["narrow_range", "bilateral"], default="narrow_range")
    parser.add_argument("--absorption-rgb", default="0.9,0.3,0.15")
    return parser.parse_args()


def read_ply_points(path):
    """The float32 x, y, z, radius rows that export_particles.cpp writes."""
    with open(path, "rb") as handle:
        header = b""
        while not header.endswith(b"end_header\n"):
            header += handle.readline()
        count = int(header.split(b"element vertex ")[1].split()[0])
        rows = np.frombuffer(handle.read(count * 16), dtype="<f4").reshape(count, 4)
    return rows[:, :3].copy(), float(np.median(rows[:, 3])) if count else 0.0


def background_texture(path):
    """The Cycles background as an sRGB 8-bit texture, rows bottom-up as VTK expects."""
    linear = metrics.read_channels(path, ["Combined.R", "Combined.G", "Combined.B"])
    encoded = (metrics.srgb_encode(linear[::-1]) * 255 + 0.5).astype(np.uint8)
    height, width = encoded.shape[:2]
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    array = numpy_support.numpy_to_vtk(encoded.reshape(-1, 3), deep=True)
    array.SetNumberOfComponents(3)
    image.GetPointData().SetScalars(array)
    texture = vtkTexture()
    texture.SetInputData(image)
    return texture


def place_camera(camera, description):
    matrix = np.array(description["world_from_camera"], dtype=float).reshape(4, 4)
    position = matrix[:3, 3]
    camera.SetPosition(*position)
    camera.SetFocalPoint(*(position - matrix[:3, 2]))  # Blender's camera looks down its local -Z
    camera.SetViewUp(*matrix[:3, 1])
    camera.SetViewAngle(description["fov_y_deg"])
    camera.SetClippingRange(description.get("near", 0.01), description.get("far", 1000.0))


def make_mapper(points, radius, filter_name, absorption_rgb):
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_support.numpy_to_vtk(points.astype(np.float32), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(vtk_points)
    mapper = vtkOpenGLFluidMapper()
    mapper.SetInputData(poly)
    mapper.SetParticleRadius(radius)
    # VTK's defaults for the filter (3 iterations, radius 5 pixels); the narrow-range filter is its own
    # recommendation, the bilateral one its older alternative.
    if filter_name == "narrow_range":
        mapper.SetSurfaceFilterMethod(vtkOpenGLFluidMapper.NarrowRange)
    else:
        mapper.SetSurfaceFilterMethod(vtkOpenGLFluidMapper.BilateralGaussian)
    mapper.SetDisplayMode(vtkOpenGLFluidMapper.TransparentFluidVolume)
    mapper.SetRefractiveIndex(1.33)
    mapper.SetAttenuationColor(*absorption_rgb)
    mapper.SetAttenuationScale(1.0)
    return mapper


def read_back(window):
    grabber = vtkWindowToImageFilter()
    grabber.SetInput(window)
    grabber.SetInputBufferTypeToRGB()
    grabber.ReadFrontBufferOff()
    grabber.Update()
    image = grabber.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = numpy_support.vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, 3)
    encoded = pixels[::-1].astype(np.float64) / 255.0
    # Undo the sRGB encoding the texture was given, so the result compares with linear references.
    return np.where(encoded <= 0.04045, encoded / 12.92, ((encoded + 0.055) / 1.055) ** 2.4)


def main():
    arguments = parse_arguments()
    description = json.load(open(arguments.scene))
    camera_description = description["camera"]
    width, height = camera_description["width"], camera_description["height"]
    points, radius = read_ply_points(arguments.particles)
    background = os.path.join(os.path.dirname(arguments.scene), description["background"]["image"])

    renderer = vtkRenderer()
    renderer.SetBackgroundTexture(background_texture(background))
    renderer.TexturedBackgroundOn()
    window = vtkRenderWindow()
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    place_camera(renderer.GetActiveCamera(), camera_description)
    volume = vtkVolume()
    absorption = [float(c) for c in arguments.absorption_rgb.split(",")]
    volume.SetMapper(make_mapper(points, radius, arguments.filter, absorption))
    renderer.AddVolume(volume)

    started = time.perf_counter()
    window.Render()
    composite = read_back(window)  # reading back waits for the GL work to finish
    first_frame_ms = (time.perf_counter() - started) * 1e3
    frame_ms = []
    for _ in range(arguments.repeats):
        started = time.perf_counter()
        window.Modified()
        volume.Modified()
        window.Render()
        read_back(window)
        frame_ms.append((time.perf_counter() - started) * 1e3)
    np.savez(arguments.output, composite=composite, frame_ms=np.array(frame_ms),
             first_frame_ms=first_frame_ms, gl_renderer=gl_renderer(window))


def gl_renderer(window):
    lines = window.ReportCapabilities().splitlines()
    return next((line.split(":", 1)[1].strip() for line in lines if "renderer string" in line), "unknown")


if __name__ == "__main__":
    main()
