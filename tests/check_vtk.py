"""check_vtk.py DIR   (run with pvpython: ParaView's own VTK readers, no display needed)

Loads every frame listed in DIR/solution.pvd with VTK's XML readers (.vtu, or .pvtu with
its pieces) and checks: each frame has points and triangles, the same counts in every
frame, a 3-component point array "displacement" and "velocity", "green_strain" as cell
data (one value per triangle, not point data), a connected mesh (fewer points than triangle
corners), and that the last frame's largest displacement reaches the largest probe
displacement in DIR/probes.csv (probes sit on vertices) within 1e-6 m.
"""

import csv
import math
import os
import re
import sys

from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader


def read_grid(path):
    reader = (vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def frame_problems(grid, counts):
    """What is wrong with one frame (empty if nothing)."""
    problems = []
    n_points, n_cells = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if n_points == 0 or n_cells == 0:
        problems.append("no points or no cells")
    for name in ("displacement", "velocity"):
        array = grid.GetPointData().GetArray(name)
        if array is None or array.GetNumberOfComponents() != 3:
            problems.append("no 3-component point array '%s'" % name)
    strain = grid.GetCellData().GetArray("green_strain")
    if strain is None or strain.GetNumberOfTuples() != n_cells:
        problems.append("no cell array 'green_strain' with one value per cell")
    if grid.GetPointData().GetArray("green_strain") is not None:
        problems.append("'green_strain' is point data")
    if n_points >= 3 * n_cells:
        problems.append("not a connected mesh (%d points, %d cells)" % (n_points, n_cells))
    if counts is not None and counts != (n_points, n_cells):
        problems.append("%d points and %d cells, the first frame has %d and %d"
                        % (n_points, n_cells, counts[0], counts[1]))
    return problems


def main(directory):
    with open(os.path.join(directory, "solution.pvd")) as pvd:
        frames = re.findall(r'file="([^"]+)"', pvd.read())
    if not frames:
        print("FAILED: no frames in %s/solution.pvd" % directory)
        return 1

    passed, counts, largest_displacement = True, None, 0.0
    for frame in frames:
        grid = read_grid(os.path.join(directory, frame))
        problems = frame_problems(grid, counts)
        if problems:
            print("FAILED: frame %s: %s" % (frame, "; ".join(problems)))
            passed = False
            continue
        counts = (grid.GetNumberOfPoints(), grid.GetNumberOfCells())
        displacement = grid.GetPointData().GetArray("displacement")
        largest_displacement = max(
            math.sqrt(sum(c * c for c in displacement.GetTuple3(i)))
            for i in range(counts[0]))

    with open(os.path.join(directory, "probes.csv")) as probes_file:
        probes = list(csv.DictReader(probes_file))
    last_step = probes[-1]["step"]
    largest_probe = max(
        math.sqrt(sum(float(row[c]) ** 2 for c in ("ux", "uy", "uz")))
        for row in probes if row["step"] == last_step)
    print("%d frames of %s points and %s cells; largest displacement in the last frame %g m, "
          "largest probe displacement %g m" % (len(frames), counts and counts[0],
                                               counts and counts[1], largest_displacement,
                                               largest_probe))
    # VTK stores the displacement in single or double precision; probes are a subset of
    # vertices.
    passed = passed and largest_displacement >= largest_probe - 1e-6
    print("PASSED" if passed else "FAILED")
    return 0 if passed else 1


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: pvpython check_vtk.py DIR")
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
