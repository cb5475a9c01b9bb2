"""check_render.py PICTURES RUN FRAMES WIDTH HEIGHT FIELD movie|no-movie
(run with pvpython; needs no display)

Checks what scripts/render.py made of the clothsim output directory RUN in PICTURES:
 - exactly FRAMES pictures frame-00000.png ... of WIDTH x HEIGHT pixels, none blank: each
   has many colours, and the cloth's colour map (Viridis) covers at least 2 % of it;
 - movie.mp4 (an MP4 container, H.264, WIDTH x HEIGHT rounded up to even, FRAMES
   frames, read by ffprobe) when asked for, none otherwise;
 - clothsim.pvsm loads in pvpython, from RUN and, with the data directory given, from a
   copy of RUN elsewhere: the reader then names the copy, has every output time, the
   deformed surface has the frames' points, and the colouring is by FIELD.
"""

import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy
from vtkmodules.numpy_interface import dataset_adapter
from vtkmodules.vtkIOImage import vtkPNGReader

N_FAILURES = 0


def check(condition, what):
    global N_FAILURES
    N_FAILURES += 0 if condition else 1
    print("  %s  %s" % ("ok  " if condition else "FAIL", what))
    return condition


def viridis(n_samples=64):
    """Samples of ParaView's "Viridis (matplotlib)" preset as 0..255 RGB."""
    from paraview import simple
    lookup = simple.GetColorTransferFunction("check_render_viridis")
    lookup.ApplyPreset("Viridis (matplotlib)", True)
    lookup.RescaleTransferFunction(0.0, 1.0)
    table = lookup.GetClientSideObject()
    samples = []
    for k in range(n_samples):
        rgb = [0.0, 0.0, 0.0]
        table.GetColor(k / (n_samples - 1), rgb)
        samples.append([255 * c for c in rgb])
    return numpy.array(samples)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = dataset_adapter.WrapDataObject(image).PointData[0]
    return width, height, numpy.asarray(pixels)[:, :3].astype(float)


def check_pictures(pictures, n_frames, width, height):
    frames = sorted(glob.glob(os.path.join(pictures, "frame-*.png")))
    check(len(frames) == n_frames, "%d frames (expected %d)" % (len(frames), n_frames))
    colour_map = viridis()
    for frame in frames:
        name = os.path.basename(frame)
        frame_width, frame_height, pixels = read_png(frame)
        check((frame_width, frame_height) == (width, height),
              "%s: %d x %d" % (name, frame_width, frame_height))
        colours, counts = numpy.unique(pixels, axis=0, return_counts=True)
        check(len(colours) > 16, "%s: %d colours" % (name, len(colours)))
        # A pixel of the colour map: its colour's direction in RGB (shading scales the
        # brightness, not the direction) within 4 degrees of a Viridis sample's, and
        # not a grey (white background, black text).
        directions = colours / numpy.maximum(numpy.linalg.norm(colours, axis=1), 1)[:, None]
        samples = colour_map / numpy.linalg.norm(colour_map, axis=1)[:, None]
        nearest = numpy.max(directions @ samples.T, axis=1)
        grey = directions @ (numpy.ones(3) / numpy.sqrt(3))
        on_map = (nearest > numpy.cos(numpy.radians(4))) & (grey < numpy.cos(numpy.radians(10)))
        share = counts[on_map].sum() / counts.sum()
        check(share >= 0.02, "%s: colour map on %.1f %% of the picture" % (name, 100 * share))


def check_movie(pictures, wanted, n_frames, width, height):
    movie = os.path.join(pictures, "movie.mp4")
    if not wanted:
        check(not os.path.exists(movie), "no movie.mp4")
        return
    if not check(os.path.isfile(movie), "movie.mp4 written"):
        return
    with open(movie, "rb") as data:
        check(data.read(12)[4:8] == b"ftyp", "movie.mp4 is an MP4 container")
    probe = subprocess.run(
        ["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
         "stream=codec_name,width,height,nb_read_frames", "-of", "json", movie],
        stdout=subprocess.PIPE, universal_newlines=True, check=True)
    stream = json.loads(probe.stdout)["streams"][0]
    check(stream["codec_name"] == "h264", "movie: codec %s" % stream["codec_name"])
    check((stream["width"], stream["height"]) == (width + width % 2, height + height % 2),
          "movie: %d x %d" % (stream["width"], stream["height"]))
    check(int(stream["nb_read_frames"]) == n_frames,
          "movie: %s frames" % stream["nb_read_frames"])


def check_state(pictures, run, field):
    from paraview import simple
    state = os.path.join(pictures, "clothsim.pvsm")
    with open(os.path.join(run, "solution.pvd")) as pvd:
        n_times = pvd.read().count("<DataSet ")
    copy = tempfile.mkdtemp(prefix="clothsim-render-state-")
    try:
        moved = os.path.join(copy, "moved-run")
        shutil.copytree(run, moved, ignore=shutil.ignore_patterns("render*", "pictures*"))
        for where, options in (("in place", {}),
                               ("moved", {"data_directory": moved,
                                          "restrict_to_data_directory": True})):
            simple.ResetSession()
            simple.LoadState(state, **options)
            reader = simple.FindSource("solution.pvd")
            if not check(reader is not None, "state %s: the reader solution.pvd" % where):
                continue
            expected = os.path.join(moved if options else os.path.abspath(run), "solution.pvd")
            check(os.path.realpath(reader.FileName) == os.path.realpath(expected),
                  "state %s: reads %s" % (where, reader.FileName))
            check(len(reader.TimestepValues) == n_times,
                  "state %s: %d output times" % (where, len(reader.TimestepValues)))
            deformed = simple.FindSource("deformed")
            deformed.UpdatePipeline(reader.TimestepValues[-1])
            check(deformed.GetDataInformation().GetNumberOfPoints() > 0,
                  "state %s: deformed surface of %d points"
                  % (where, deformed.GetDataInformation().GetNumberOfPoints()))
            view = simple.GetRenderViews()[0]
            coloured = simple.GetDisplayProperties(deformed, view).ColorArrayName[1]
            check(coloured == field, "state %s: coloured by %s" % (where, coloured))
    finally:
        shutil.rmtree(copy)


def main(arguments):
    if len(arguments) != 7 or arguments[6] not in ("movie", "no-movie"):
        print(__doc__)
        return 2
    pictures, run, n_frames, width, height, field, movie = arguments
    n_frames, width, height = int(n_frames), int(width), int(height)
    check_pictures(pictures, n_frames, width, height)
    check_movie(pictures, movie == "movie", n_frames, width, height)
    check_state(pictures, run, field)
    print("PASSED" if N_FAILURES == 0 else "FAILED (%d)" % N_FAILURES)
    return 0 if N_FAILURES == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
