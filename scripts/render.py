"""Renders a clothsim output directory with ParaView: PNG frames, a movie, a state file.

Run with ParaView's batch client (scripts/render.sh starts it under xvfb-run when there is
no display):

    pvbatch scripts/render.py output/default
    pvbatch scripts/render.py output/drape --field green_strain --view front --stride 2 \\
        --size 1280x720 --output /tmp/drape-pictures --no-movie

Reads DIR/solution.pvd (.vtu frames, or .pvtu with one piece per rank), shows the deformed
surface (the frames hold the reference positions: Warp By Vector on `displacement`, scale
1), coloured by one field with a fixed colour range over all rendered frames, from a fixed
camera that frames the surface's bounds over the whole run. Writes into the output folder
(default DIR/render):

    frame-NNNNN.png   one picture per rendered frame (every STRIDE-th output time, and the last)
    movie.mp4         the frames at --fps frames per second (H.264, assembled by ffmpeg)
    clothsim.pvsm     a ParaView state with the same pipeline, colours and camera

Open the state in the ParaView GUI with File > Load State. It names solution.pvd by its
absolute path; for a directory that has moved, choose "Search files under specified
directory" in the dialog and give the directory that now holds solution.pvd.
"""

import argparse
import math
import os
import shutil
import subprocess
import sys

# Units of the fields clothsim writes (README, "Output").
UNITS = {
    "displacement": "m",
    "velocity": "m/s",
    "green_strain": "1",
    "membrane_stress": "N/m",
    "spring_strain": "1",
    "curvature_change": "1/m",
    "rank": "",
}
# Camera directions (from the surface's centre towards the camera) and up vectors, for
# scenes with z up (gravity along -z): front is the side of -y.
VIEWS = {
    "front": ((0, -1, 0), (0, 0, 1)),
    "back": ((0, 1, 0), (0, 0, 1)),
    "left": ((-1, 0, 0), (0, 0, 1)),
    "right": ((1, 0, 0), (0, 0, 1)),
    "top": ((0, 0, 1), (0, 1, 0)),
    "bottom": ((0, 0, -1), (0, 1, 0)),
    "iso": ((0.6, -1.0, 0.7), (0, 0, 1)),
}
COMPONENTS = {"magnitude": "Magnitude", "x": "X", "y": "Y", "z": "Z"}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        prog="render.py",
        description="PNG frames, a movie and a ParaView state file of a clothsim run.",
    )
    parser.add_argument("directory", help="a clothsim output directory (holds solution.pvd)")
    parser.add_argument("--output", help="folder for the pictures (default: DIRECTORY/render)")
    parser.add_argument("--size", default="1024x768", help="picture size WxH in pixels")
    parser.add_argument(
        "--field",
        help="colour by this point or cell array, optionally with a component: "
        "NAME, NAME:magnitude, NAME:x|y|z (default: displacement's magnitude)",
    )
    parser.add_argument("--view", default="iso", choices=sorted(VIEWS),
                        help="camera on the side -y (front), +y (back), -x (left), +x "
                        "(right), +z (top), -z (bottom), or iso: from +x, -y, +z")
    parser.add_argument("--stride", type=int, default=1, help="render every N-th frame")
    parser.add_argument("--fps", type=int, default=15, help="movie frames per second")
    movie = parser.add_mutually_exclusive_group()
    movie.add_argument("--movie", dest="movie", action="store_true", default=True,
                       help="assemble movie.mp4 with ffmpeg (the default)")
    movie.add_argument("--no-movie", dest="movie", action="store_false")
    arguments = parser.parse_args(argv)
    try:
        width, height = (int(n) for n in arguments.size.lower().split("x"))
    except ValueError:
        parser.error("--size: expected WxH, e.g. 1024x768, got '%s'" % arguments.size)
    if width < 16 or height < 16 or width > 8192 or height > 8192:
        parser.error("--size: each side between 16 and 8192 pixels")
    arguments.width, arguments.height = width, height
    if arguments.stride < 1:
        parser.error("--stride: at least 1")
    if arguments.fps < 1:
        parser.error("--fps: at least 1")
    arguments.directory = os.path.abspath(arguments.directory)
    arguments.pvd = os.path.join(arguments.directory, "solution.pvd")
    if not os.path.isfile(arguments.pvd):
        parser.error("%s: not found (not a clothsim output directory?)" % arguments.pvd)
    arguments.output = os.path.abspath(arguments.output or
                                       os.path.join(arguments.directory, "render"))
    if arguments.movie and shutil.which("ffmpeg") is None:
        parser.error("--movie needs ffmpeg (Debian package ffmpeg); or pass --no-movie")
    return arguments


def choose_field(reader, spec):
    """(association, name, component, title) of the array to colour by."""
    point_arrays = list(reader.PointData.keys())
    cell_arrays = list(reader.CellData.keys())
    name, _, component = (spec or "displacement").partition(":")
    if name in point_arrays:
        association, array = "POINTS", reader.PointData[name]
    elif name in cell_arrays:
        association, array = "CELLS", reader.CellData[name]
    else:
        sys.exit("render.py: no array '%s' in the frames; point arrays: %s; cell arrays: %s"
                 % (name, ", ".join(point_arrays), ", ".join(cell_arrays)))
    if array.GetNumberOfComponents() == 1:
        if component not in ("", "magnitude"):
            sys.exit("render.py: '%s' has one component" % name)
        component = ""
    else:
        component = component.lower() or "magnitude"
        if component not in COMPONENTS:
            sys.exit("render.py: component '%s': expected magnitude, x, y or z" % component)
    unit = UNITS.get(name)
    title = name + ("" if not component else " " + component)
    if unit:
        title += " (%s)" % unit
    return association, name, COMPONENTS.get(component, ""), title


def data_range(source, association, name, component, times):
    """The array's range over the given times (component -1: magnitude)."""
    index = {"": 0, "Magnitude": -1, "X": 0, "Y": 1, "Z": 2}[component]
    low, high = math.inf, -math.inf
    for time in times:
        source.UpdatePipeline(time)
        info = source.GetDataInformation()
        arrays = (info.GetPointDataInformation() if association == "POINTS"
                  else info.GetCellDataInformation())
        array = arrays.GetArrayInformation(name)
        first, last = array.GetComponentRange(index)
        low, high = min(low, first), max(high, last)
    if not low < high:  # a constant field: widen so that the colour map stays defined
        pad = max(abs(low), 1.0) * 1e-6
        low, high = low - pad, high + pad
    return low, high


def union_of_bounds(source, times):
    bounds = [math.inf, -math.inf] * 3
    for time in times:
        source.UpdatePipeline(time)
        frame = source.GetDataInformation().GetBounds()
        for axis in range(3):
            bounds[2 * axis] = min(bounds[2 * axis], frame[2 * axis])
            bounds[2 * axis + 1] = max(bounds[2 * axis + 1], frame[2 * axis + 1])
    return bounds


def place_camera(view, bounds, direction, up, width, height):
    """Looks at the centre of `bounds` along -direction from far enough away that the
    bounding sphere fits the picture's left 80 % (the scalar bar takes the right; a fixed
    camera for the whole run)."""
    centre = [(bounds[2 * a] + bounds[2 * a + 1]) / 2 for a in range(3)]
    radius = 0.5 * math.sqrt(sum((bounds[2 * a + 1] - bounds[2 * a]) ** 2 for a in range(3)))
    radius = max(radius, 1e-9)
    length = math.sqrt(sum(c * c for c in direction))
    unit = [c / length for c in direction]
    view_angle = 30.0  # vertical
    half_vertical = math.radians(view_angle) / 2
    half_horizontal = math.atan(math.tan(half_vertical) * width / height)
    half = min(half_vertical, math.atan(0.8 * math.tan(half_horizontal)))
    distance = 1.05 * radius / math.sin(half)
    # Right in the picture: (towards the surface) x up; the camera moves right by a tenth
    # of the picture's width so that the surface sits left of the scalar bar.
    right = [-unit[1] * up[2] + unit[2] * up[1], -unit[2] * up[0] + unit[0] * up[2],
             -unit[0] * up[1] + unit[1] * up[0]]
    norm = math.sqrt(sum(c * c for c in right)) or 1.0
    shift = 0.1 * 2 * distance * math.tan(half_horizontal)
    focal = [centre[a] + shift * right[a] / norm for a in range(3)]
    view.CameraFocalPoint = focal
    view.CameraPosition = [focal[a] + distance * unit[a] for a in range(3)]
    view.CameraViewUp = list(up)
    view.CameraViewAngle = view_angle
    view.CameraParallelProjection = 0
    view.CenterOfRotation = centre


def main(argv):
    arguments = parse_arguments(argv)
    import paraview.simple as pv  # after the arguments: --help needs no ParaView

    os.makedirs(arguments.output, exist_ok=True)
    for old in os.listdir(arguments.output):  # frames of an earlier, longer rendering
        if old.startswith("frame-") and old.endswith(".png"):
            os.remove(os.path.join(arguments.output, old))
    reader = pv.PVDReader(registrationName="solution.pvd", FileName=arguments.pvd)
    values = reader.TimestepValues  # a number for a single frame
    times = [values] if isinstance(values, float) else (list(values) or [0.0])
    rendered = times[:: arguments.stride]
    if rendered[-1] != times[-1]:
        rendered.append(times[-1])
    association, name, component, title = choose_field(reader, arguments.field)

    warped = pv.WarpByVector(registrationName="deformed", Input=reader)
    warped.Vectors = ["POINTS", "displacement"]
    warped.ScaleFactor = 1.0

    view = pv.CreateView("RenderView")
    view.ViewSize = [arguments.width, arguments.height]
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0
    display = pv.Show(warped, view)
    display.Representation = "Surface"
    # More ambient light than ParaView's default: a sheet seen at an angle keeps the
    # colours of its colour map, the shading still shows the folds.
    display.Ambient, display.Diffuse = 0.35, 0.65
    pv.ColorBy(display, (association, name, component) if component else (association, name))
    lookup = pv.GetColorTransferFunction(name)
    lookup.ApplyPreset("Viridis (matplotlib)", True)
    if component:
        lookup.VectorMode = "Magnitude" if component == "Magnitude" else "Component"
        lookup.VectorComponent = {"Magnitude": 0, "X": 0, "Y": 1, "Z": 2}[component]
    low, high = data_range(warped, association, name, component, rendered)
    lookup.AutomaticRescaleRangeMode = "Never"
    lookup.RescaleTransferFunction(low, high)
    pv.GetOpacityTransferFunction(name).RescaleTransferFunction(low, high)
    bar = pv.GetScalarBar(lookup, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.RangeLabelFormat = "%-#.3g"
    bar.Visibility = 1
    display.SetScalarBarVisibility(view, True)

    clock = pv.Text(registrationName="time")
    clock_display = pv.Show(clock, view)
    clock_display.WindowLocation = "Upper Left Corner"
    clock_display.Color = [0.1, 0.1, 0.1]
    clock_display.FontSize = 14

    direction, up = VIEWS[arguments.view]
    place_camera(view, union_of_bounds(warped, rendered), direction, up,
                 arguments.width, arguments.height)

    scene = pv.GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    frames = []
    for number, time in enumerate(rendered):
        clock.Text = "t = %.4g s" % time
        scene.AnimationTime = time
        view.ViewTime = time
        path = os.path.join(arguments.output, "frame-%05d.png" % number)
        pv.SaveScreenshot(path, view, ImageResolution=[arguments.width, arguments.height])
        frames.append(path)
    clock.Text = "t = %.4g s" % rendered[-1]

    state = os.path.join(arguments.output, "clothsim.pvsm")
    pv.SaveState(state)
    print("render.py: %d frames of %dx%d in %s (%s, range %.4g to %.4g); state %s"
          % (len(frames), arguments.width, arguments.height, arguments.output, title, low,
             high, state))

    if arguments.movie:
        movie = os.path.join(arguments.output, "movie.mp4")
        # H.264 in yuv420p (what players and browsers accept) needs even sides.
        command = ["ffmpeg", "-v", "error", "-y", "-framerate", str(arguments.fps),
                   "-i", os.path.join(arguments.output, "frame-%05d.png"),
                   "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2:color=white",
                   "-c:v", "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart",
                   movie]
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True)
        if result.returncode != 0:
            sys.exit("render.py: ffmpeg failed (%d): %s" % (result.returncode, result.stdout))
        print("render.py: movie %s" % movie)


if __name__ == "__main__":
    main(sys.argv[1:])
