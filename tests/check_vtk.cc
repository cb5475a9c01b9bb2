// check_vtk DIR
// Loads every frame listed in DIR/solution.pvd with VTK's XML readers (.vtu or .pvtu with
// its pieces) and checks: each frame has points and triangles, the same counts in every
// frame, a 3-component "displacement" and "velocity", and the last frame's largest
// displacement equals the largest probe displacement in DIR/probes.csv (probes sit on
// vertices) within 1e-6 m.

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "csv.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <regex>

int
main(int argc, char **argv)
{
  if (argc != 2)
    {
      std::cerr << "usage: check_vtk DIR\n";
      return 2;
    }
  const std::string        directory = argv[1];
  std::ifstream            pvd(directory + "/solution.pvd");
  const std::string        text((std::istreambuf_iterator<char>(pvd)),
                         std::istreambuf_iterator<char>());
  std::vector<std::string> frames;
  const std::regex         file_attribute("file=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), file_attribute);
       it != std::sregex_iterator();
       ++it)
    frames.push_back((*it)[1]);
  if (frames.empty())
    {
      std::cout << "FAILED: no frames in " << directory << "/solution.pvd\n";
      return 1;
    }

  bool      passed   = true;
  vtkIdType n_points = -1, n_cells = -1;
  double    largest_displacement = 0.;
  for (const std::string &frame : frames)
    {
      vtkSmartPointer<vtkUnstructuredGrid> grid;
      const std::string                    path = directory + "/" + frame;
      if (frame.size() > 5 && frame.substr(frame.size() - 5) == ".pvtu")
        {
          auto reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
          reader->SetFileName(path.c_str());
          reader->Update();
          grid = reader->GetOutput();
        }
      else
        {
          auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
          reader->SetFileName(path.c_str());
          reader->Update();
          grid = reader->GetOutput();
        }
      vtkDataArray *displacement = grid->GetPointData()->GetArray("displacement");
      vtkDataArray *velocity     = grid->GetPointData()->GetArray("velocity");
      if (grid->GetNumberOfPoints() == 0 || grid->GetNumberOfCells() == 0 ||
          displacement == nullptr || velocity == nullptr ||
          displacement->GetNumberOfComponents() != 3 ||
          velocity->GetNumberOfComponents() != 3 ||
          grid->GetCellData()->GetArray("green_strain") == nullptr ||
          grid->GetCellData()->GetArray("green_strain")->GetNumberOfTuples() !=
            grid->GetNumberOfCells() ||
          grid->GetPointData()->GetArray("green_strain") != nullptr ||
          // A connected mesh: fewer points than triangle corners.
          grid->GetNumberOfPoints() >= 3 * grid->GetNumberOfCells() ||
          (n_cells >= 0 && (grid->GetNumberOfCells() != n_cells ||
                            grid->GetNumberOfPoints() != n_points)))
        {
          std::cout << "FAILED: frame " << frame
                    << " is missing data or has other counts\n";
          passed = false;
          continue;
        }
      n_points             = grid->GetNumberOfPoints();
      n_cells              = grid->GetNumberOfCells();
      largest_displacement = 0.;
      for (vtkIdType i = 0; i < n_points; ++i)
        {
          double value[3];
          displacement->GetTuple(i, value);
          largest_displacement =
            std::max(largest_displacement, std::hypot(value[0], value[1], value[2]));
        }
    }

  const auto probes        = clothsim::test::read_csv(directory + "/probes.csv");
  double     largest_probe = 0.;
  const auto last_step     = probes.rows.back()[probes.column("step")];
  for (unsigned int r = 0; r < probes.rows.size(); ++r)
    if (probes.rows[r][probes.column("step")] == last_step)
      largest_probe = std::max(largest_probe,
                               std::hypot(probes.number(r, "ux"),
                                          probes.number(r, "uy"),
                                          probes.number(r, "uz")));
  std::cout << frames.size() << " frames of " << n_points << " points and " << n_cells
            << " cells; largest displacement in the last frame " << largest_displacement
            << " m, largest probe displacement " << largest_probe << " m\n";
  // VTK stores the displacement in single or double precision; probes are a subset of
  // vertices.
  passed = passed && largest_displacement >= largest_probe - 1e-6;
  std::cout << (passed ? "PASSED" : "FAILED") << std::endl;
  return passed ? 0 : 1;
}
