"""vtu_writer_read.py DIR   (run with pvpython: ParaView's VTK XML readers, no display)

The reading side of the vtu_writer unit test: reads back every file that DIR/expected.json
lists (written by tests/vtu_writer.cc through io::write_vtu_frame) and checks the number of
points and cells, that every cell is a VTK_TRIANGLE with the vertices written, every
coordinate (Float64, 1e-15 relative), each point field as point data only and each cell
field as cell data only (components, tuples, Float64, every value 1e-15 relative), and the
TIME field data. A .pvtu holds the pieces of all ranks concatenated in rank order.
"""

import json
import os
import sys

from vtkmodules.vtkCommonCore import VTK_DOUBLE, vtkIdList
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

N_CHECKS, N_FAILURES = 0, 0


def check(condition, what):
    global N_CHECKS, N_FAILURES
    N_CHECKS += 1
    if not condition:
        N_FAILURES += 1
    print("  %s: %s" % ("ok" if condition else "FAILED", what))
    return condition


def relative_difference(value, expected):
    scale = max(abs(value), abs(expected))
    return 0.0 if scale == 0.0 else abs(value - expected) / scale


def check_array(arrays, others, kind, field, what):
    name, n_components, values = field["name"], field["components"], field["values"]
    array = arrays.GetArray(name)
    check(array is not None, "%s: %s array '%s' present" % (what, kind, name))
    check(others.GetArray(name) is None, "%s: '%s' is %s data only" % (what, name, kind))
    if array is None:
        return
    check(array.GetNumberOfComponents() == n_components,
          "%s: '%s' components %d, expected %d"
          % (what, name, array.GetNumberOfComponents(), n_components))
    check(array.GetNumberOfTuples() == len(values) // n_components,
          "%s: '%s' tuples %d, expected %d"
          % (what, name, array.GetNumberOfTuples(), len(values) // n_components))
    check(array.GetDataType() == VTK_DOUBLE, "%s: '%s' is Float64" % (what, name))
    if array.GetNumberOfValues() != len(values):
        return
    largest = max((relative_difference(array.GetComponent(k // n_components, k % n_components),
                                       value) for k, value in enumerate(values)), default=0.0)
    check(largest <= 1e-15, "%s: '%s' %d values, largest relative difference %g <= 1e-15"
          % (what, name, len(values), largest))


def check_grid(grid, case, time):
    what = case["file"]
    points, triangles = case["points"], case["triangles"]
    n_points, n_cells = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    check(n_points == len(points), "%s: points %d, expected %d" % (what, n_points, len(points)))
    check(n_cells == len(triangles),
          "%s: cells %d, expected %d" % (what, n_cells, len(triangles)))
    if n_points != len(points) or n_cells != len(triangles):
        return

    n_triangles, n_wrong_vertices, ids = 0, 0, vtkIdList()
    for c in range(n_cells):
        n_triangles += grid.GetCellType(c) == VTK_TRIANGLE
        grid.GetCellPoints(c, ids)
        n_wrong_vertices += ids.GetNumberOfIds() != 3 or [
            ids.GetId(v) for v in range(3)] != triangles[c]
    check(n_triangles == n_cells,
          "%s: cells of type VTK_TRIANGLE %d of %d" % (what, n_triangles, n_cells))
    check(n_wrong_vertices == 0,
          "%s: cells with vertices differing from those written: %d" % (what, n_wrong_vertices))

    if n_points > 0:
        check(grid.GetPoints().GetDataType() == VTK_DOUBLE, "%s: points are Float64" % what)
    largest = max((relative_difference(grid.GetPoint(p)[d], points[p][d])
                   for p in range(n_points) for d in range(3)), default=0.0)
    check(largest <= 1e-15,
          "%s: point coordinates, largest relative difference %g <= 1e-15" % (what, largest))

    for field in case["point_fields"]:
        check_array(grid.GetPointData(), grid.GetCellData(), "point", field, what)
    for field in case["cell_fields"]:
        check_array(grid.GetCellData(), grid.GetPointData(), "cell", field, what)

    read_time = grid.GetFieldData().GetArray("TIME")
    value = (read_time.GetComponent(0, 0)
             if read_time is not None and read_time.GetNumberOfTuples() == 1 else None)
    check(value == time, "%s: TIME %r, expected %r" % (what, value, time))


def main(directory):
    with open(os.path.join(directory, "expected.json")) as description:
        expected = json.load(description)
    print("reading back %d file(s) written on %d rank(s) in %s"
          % (len(expected["cases"]), expected["ranks"], directory))
    for case in expected["cases"]:
        path = os.path.join(directory, case["file"])
        check(os.path.isfile(path), "%s exists" % case["file"])
        reader = (vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
                  else vtkXMLUnstructuredGridReader())
        reader.SetFileName(path)
        reader.Update()
        check_grid(reader.GetOutput(), case, expected["time"])
    print("%d of %d checks passed" % (N_CHECKS - N_FAILURES, N_CHECKS))
    print("PASSED" if N_FAILURES == 0 else "FAILED")
    return 0 if N_FAILURES == 0 else 1


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print("usage: pvpython vtu_writer_read.py DIR")
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
