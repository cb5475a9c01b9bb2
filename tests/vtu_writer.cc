// Unit test of clothsim::io::write_vtu_frame: writes triangle pieces with point and cell
// fields, reads them back with VTK's XML readers and checks the counts, the cell types,
// the connectivity, every coordinate and field value (1e-15 relative), that cell fields
// are cell data, and the TIME field data. On one rank: a 2 x 2 square (9 shared points,
// 8 triangles), a 63 x 63 grid (4096 points: arrays of exactly 1 and 3 full compression
// blocks, and coordinates in many blocks with a partial last one) and an empty piece. On
// several ranks: a different piece per rank, read back through the .pvtu by rank 0. Both:
// a directory that does not exist and a field of the wrong size (on the last rank only)
// make every rank throw. With an argument, the files are kept in that directory.

#include <deal.II/base/utilities.h>

#include "io/vtu_writer.h"
#include "test_support.h"

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace clothsim::io;
using namespace clothsim::test;

namespace
{
  // Relative difference of a read value from the written one.
  double
  relative_difference(const double value, const double expected)
  {
    const double scale = std::max(std::abs(value), std::abs(expected));
    return scale == 0. ? 0. : std::abs(value - expected) / scale;
  }

  struct Frame
  {
    SurfacePiece piece;
    FrameData    data;
  };

  // An nx x ny grid of 0.5 m squares, two triangles each, starting at x = x0, with
  // irrational coordinates and field values that differ per vertex, triangle and `seed`.
  Frame
  make_frame(const unsigned int nx,
             const unsigned int ny,
             const double       x0,
             const unsigned int seed)
  {
    Frame frame;
    for (unsigned int j = 0; j <= ny; ++j)
      for (unsigned int i = 0; i <= nx; ++i)
        frame.piece.points.push_back(
          {{x0 + 0.5 * i, 0.5 * j, 0.1 * std::sin(i + 2. * j + seed)}});
    for (unsigned int j = 0; j < ny; ++j)
      for (unsigned int i = 0; i < nx; ++i)
        {
          const unsigned int v0 = j * (nx + 1) + i, v1 = v0 + 1, v2 = v0 + nx + 1,
                             v3 = v2 + 1;
          frame.piece.triangles.push_back({{v0, v1, v3}});
          frame.piece.triangles.push_back({{v0, v3, v2}});
        }
    const std::size_t n_points = frame.piece.points.size();
    const std::size_t n_cells  = frame.piece.triangles.size();

    Field displacement{"displacement", 3, {}}, speed{"speed", 1, {}};
    for (std::size_t k = 0; k < 3 * n_points; ++k)
      displacement.values.push_back(1e-3 * std::sin(0.7 * k + seed));
    for (std::size_t k = 0; k < n_points; ++k)
      speed.values.push_back(std::exp(-0.01 * k) / (3. + seed));
    Field green_strain{"green_strain", 1, {}}, stress{"membrane_stress", 3, {}};
    for (std::size_t c = 0; c < n_cells; ++c)
      green_strain.values.push_back(1e-4 * (1. + c) + 1e-7 * seed / 3.);
    for (std::size_t k = 0; k < 3 * n_cells; ++k)
      stress.values.push_back(1e3 * std::cos(0.3 * k + seed));
    frame.data.point_fields = {displacement, speed};
    frame.data.cell_fields  = {green_strain, stress};
    return frame;
  }

  // Compares one field of the written pieces (concatenated) with the array read back.
  void
  check_array(ConditionalOStream &out,
              vtkFieldData       *read,
              vtkFieldData       *other,
              const std::string  &kind,
              const Field        &field,
              const std::string  &what)
  {
    vtkDataArray *array = read->GetArray(field.name.c_str());
    check(out,
          array != nullptr,
          what + ": " + kind + " array '" + field.name + "' present");
    check(out,
          other->GetArray(field.name.c_str()) == nullptr,
          what + ": '" + field.name + "' is " + kind + " data only");
    if (array == nullptr)
      return;
    check_equal(out,
                what + ": '" + field.name + "' components",
                array->GetNumberOfComponents(),
                static_cast<int>(field.n_components));
    check_equal(out,
                what + ": '" + field.name + "' tuples",
                static_cast<std::size_t>(array->GetNumberOfTuples()),
                field.values.size() / field.n_components);
    check(out,
          array->GetDataType() == VTK_DOUBLE,
          what + ": '" + field.name + "' is Float64");
    if (array->GetNumberOfValues() != static_cast<vtkIdType>(field.values.size()))
      return;
    double largest = 0.;
    for (std::size_t k = 0; k < field.values.size(); ++k)
      largest = std::max(largest,
                         relative_difference(array->GetComponent(k / field.n_components,
                                                                 k % field.n_components),
                                             field.values[k]));
    check_at_most(out,
                  what + ": '" + field.name + "' " + std::to_string(field.values.size()) +
                    " values, largest relative difference",
                  largest,
                  1e-15);
  }

  // Checks a grid read back against the pieces written, concatenated in rank order.
  void
  check_grid(ConditionalOStream       &out,
             vtkUnstructuredGrid      *grid,
             const std::vector<Frame> &frames,
             const std::string        &what)
  {
    Frame all = frames[0];
    for (std::size_t f = 1; f < frames.size(); ++f)
      {
        const unsigned int shift = all.piece.points.size();
        const Frame       &frame = frames[f];
        all.piece.points.insert(all.piece.points.end(),
                                frame.piece.points.begin(),
                                frame.piece.points.end());
        for (auto triangle : frame.piece.triangles)
          {
            for (unsigned int &vertex : triangle)
              vertex += shift;
            all.piece.triangles.push_back(triangle);
          }
        for (std::size_t i = 0; i < all.data.point_fields.size(); ++i)
          all.data.point_fields[i].values.insert(
            all.data.point_fields[i].values.end(),
            frame.data.point_fields[i].values.begin(),
            frame.data.point_fields[i].values.end());
        for (std::size_t i = 0; i < all.data.cell_fields.size(); ++i)
          all.data.cell_fields[i].values.insert(all.data.cell_fields[i].values.end(),
                                                frame.data.cell_fields[i].values.begin(),
                                                frame.data.cell_fields[i].values.end());
      }
    const auto n_points = static_cast<vtkIdType>(all.piece.points.size());
    const auto n_cells  = static_cast<vtkIdType>(all.piece.triangles.size());
    check_equal(out, what + ": points", grid->GetNumberOfPoints(), n_points);
    check_equal(out, what + ": cells", grid->GetNumberOfCells(), n_cells);
    if (grid->GetNumberOfPoints() != n_points || grid->GetNumberOfCells() != n_cells)
      return;

    vtkIdType         n_triangles = 0, n_wrong_vertices = 0;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < n_cells; ++c)
      {
        n_triangles += grid->GetCellType(c) == VTK_TRIANGLE ? 1 : 0;
        grid->GetCellPoints(c, ids);
        for (unsigned int v = 0; v < 3; ++v)
          n_wrong_vertices +=
            ids->GetNumberOfIds() != 3 || ids->GetId(v) != all.piece.triangles[c][v];
      }
    check_equal(out, what + ": cells of type VTK_TRIANGLE", n_triangles, n_cells);
    check_equal(out,
                what + ": cell vertices differing from those written",
                n_wrong_vertices,
                vtkIdType(0));

    double largest = 0.;
    for (vtkIdType p = 0; p < n_points; ++p)
      for (unsigned int d = 0; d < 3; ++d)
        largest =
          std::max(largest,
                   relative_difference(grid->GetPoint(p)[d], all.piece.points[p][d]));
    check(out,
          grid->GetPoints()->GetDataType() == VTK_DOUBLE,
          what + ": points are Float64");
    check_at_most(out,
                  what + ": point coordinates, largest relative difference",
                  largest,
                  1e-15);

    for (const Field &field : all.data.point_fields)
      check_array(out, grid->GetPointData(), grid->GetCellData(), "point", field, what);
    for (const Field &field : all.data.cell_fields)
      check_array(out, grid->GetCellData(), grid->GetPointData(), "cell", field, what);
  }

  // TIME as read back, NaN if there is none.
  double
  read_time(vtkUnstructuredGrid *grid)
  {
    vtkDataArray *time = grid->GetFieldData()->GetArray("TIME");
    return time != nullptr && time->GetNumberOfTuples() == 1 ? time->GetComponent(0, 0)
                                                             : std::nan("");
  }

  vtkUnstructuredGrid *
  read_vtu(vtkXMLUnstructuredGridReader *reader, const std::string &path)
  {
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  }

  // Expects write_vtu_frame to throw on every rank, with `text` in the message.
  void
  check_throws(ConditionalOStream &out,
               const std::string  &what,
               const std::string  &directory,
               const Frame        &frame,
               const std::string  &text)
  {
    std::string message;
    try
      {
        write_vtu_frame(directory, "bad", frame.piece, frame.data, 0., MPI_COMM_WORLD);
      }
    catch (const std::runtime_error &e)
      {
        message = e.what();
      }
    check(out,
          message.find(text) != std::string::npos,
          what + ": throws with '" + text + "' in the message: '" + message + "'");
  }
} // namespace


int
main(int argc, char **argv)
{
  Environment         env(argc, argv);
  ConditionalOStream &out       = env.pcout;
  const unsigned int  n_ranks   = Utilities::MPI::n_mpi_processes(env.communicator);
  const unsigned int  this_rank = Utilities::MPI::this_mpi_process(env.communicator);
  const double        time      = 1.2345678901234567;

  const bool  keep = argc > 1;
  std::string directory;
  if (this_rank == 0)
    {
      if (keep)
        directory = argv[1];
      else
        {
          std::string name =
            (std::filesystem::temp_directory_path() / "clothsim-vtu-XXXXXX").string();
          if (mkdtemp(name.data()) == nullptr)
            throw std::runtime_error("cannot create a temporary directory");
          directory = name;
        }
      std::filesystem::create_directories(directory);
      out << "writing into " << directory << " on " << n_ranks << " rank(s)\n";
    }
  directory = Utilities::MPI::broadcast(env.communicator, directory, 0);

  if (n_ranks == 1)
    {
      // The 2 x 2 square, the 63 x 63 grid and an empty piece, each read back.
      const std::vector<std::pair<std::string, Frame>> cases = {
        {"square", make_frame(2, 2, 0., 0)},
        {"grid", make_frame(63, 63, 0., 1)},
        {"empty", make_frame(0, 0, 0., 2)}};
      for (const auto &[stem, frame] : cases)
        {
          Frame written = frame;
          if (stem == "empty")
            {
              written.piece = SurfacePiece();
              for (Field &field : written.data.point_fields)
                field.values.clear();
              for (Field &field : written.data.cell_fields)
                field.values.clear();
            }
          const std::string record = write_vtu_frame(
            directory, stem, written.piece, written.data, time, env.communicator);
          check_equal(out, stem + ": record", record, stem + ".vtu");
          vtkNew<vtkXMLUnstructuredGridReader> reader;
          vtkUnstructuredGrid *grid = read_vtu(reader, directory + "/" + record);
          check_grid(out, grid, {written}, stem);
          check_equal(out, stem + ": TIME", read_time(grid), time);
        }
    }
  else
    {
      // Rank r writes a (2 + r) x 2 grid shifted by 10 r m in x.
      const auto frame_of = [](const unsigned int r) {
        return make_frame(2 + r, 2, 10. * r, r);
      };
      const Frame       mine   = frame_of(this_rank);
      const std::string record = write_vtu_frame(
        directory, "pieces", mine.piece, mine.data, time, env.communicator);
      check_equal(out, "pieces: record", record, std::string("pieces.pvtu"));
      if (this_rank == 0)
        {
          std::vector<Frame> frames;
          std::size_t        points_sum = 0, cells_sum = 0;
          for (unsigned int r = 0; r < n_ranks; ++r)
            {
              frames.push_back(frame_of(r));
              points_sum += frames.back().piece.points.size();
              cells_sum += frames.back().piece.triangles.size();
            }
          out << "  " << n_ranks << " pieces: " << points_sum << " points, " << cells_sum
              << " triangles in all\n";
          vtkNew<vtkXMLPUnstructuredGridReader> reader;
          reader->SetFileName((directory + "/" + record).c_str());
          reader->Update();
          check_grid(out, reader->GetOutput(), frames, "pvtu");
          check_equal(out, "pvtu: TIME", read_time(reader->GetOutput()), time);

          // Every piece on its own, with its TIME.
          for (unsigned int r = 0; r < n_ranks; ++r)
            {
              const std::string piece =
                "pieces." + Utilities::int_to_string(r, 4) + ".vtu";
              vtkNew<vtkXMLUnstructuredGridReader> piece_reader;
              vtkUnstructuredGrid *grid = read_vtu(piece_reader, directory + "/" + piece);
              check_grid(out, grid, {frames[r]}, piece);
              check_equal(out, piece + ": TIME", read_time(grid), time);
            }
        }
    }

  // Errors: a missing directory, and a field of the wrong size on the last rank only,
  // which every rank reports with that rank's path.
  const Frame frame = make_frame(2, 2, 0., 0);
  check_throws(out,
               "missing directory",
               directory + "/no-such-directory",
               frame,
               directory + "/no-such-directory/bad.");
  Frame wrong = frame;
  if (this_rank == n_ranks - 1)
    wrong.data.cell_fields[0].values.pop_back();
  check_throws(out,
               "wrong field size",
               directory,
               wrong,
               (n_ranks == 1
                  ? std::string("bad.vtu")
                  : "bad." + Utilities::int_to_string(n_ranks - 1, 4) + ".vtu") +
                 ": field 'green_strain' has 7 values, expected 8");

  const unsigned int total_checks =
    Utilities::MPI::sum(tally().n_checks, env.communicator);
  const unsigned int total_failures =
    Utilities::MPI::sum(tally().n_failures, env.communicator);
  MPI_Barrier(env.communicator);
  if (this_rank == 0 && !keep)
    std::filesystem::remove_all(directory);
  out << total_checks - total_failures << " of " << total_checks << " checks passed on "
      << n_ranks << " rank(s)\n";
  return finish(out, total_failures == 0);
}
