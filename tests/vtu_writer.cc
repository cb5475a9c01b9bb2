// Unit test of clothsim::io::write_vtu_frame, writing side: writes triangle pieces with
// point and cell fields into DIR and describes them in DIR/expected.json (every
// coordinate, triangle and value to 17 digits); tests/vtu_writer_read.py then reads the
// files back with ParaView's VTK XML readers and checks the counts, the cell types, the
// connectivity, every coordinate and field value (1e-15 relative), that cell fields are
// cell data, and the TIME field data. On one rank: a 2 x 2 square (9 shared points, 8
// triangles), a 63 x 63 grid (4096 points: arrays of exactly 1 and 3 full compression
// blocks, and coordinates in many blocks with a partial last one) and an empty piece. On
// several ranks: a different piece per rank, described as the .pvtu (pieces concatenated
// in rank order) and as each piece. Both: a directory that does not exist and a field of
// the wrong size (on the last rank only) make every rank throw.
// Usage: vtu_writer DIR (created if missing; the files are kept for the reader).

#include <deal.II/base/utilities.h>

#include "io/vtu_writer.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace clothsim::io;
using namespace clothsim::test;

namespace
{
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

  // The pieces concatenated in rank order, as the .pvtu reads them.
  Frame
  concatenated(const std::vector<Frame> &frames)
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
    return all;
  }

  // A number to 17 significant digits: read back exactly.
  std::string
  exact(const double value)
  {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", value);
    return text;
  }

  void
  write_fields(std::ostream &json, const std::vector<Field> &fields)
  {
    json << '[';
    for (std::size_t f = 0; f < fields.size(); ++f)
      {
        json << (f == 0 ? "" : ",") << "\n    {\"name\": \"" << fields[f].name
             << "\", \"components\": " << fields[f].n_components << ", \"values\": [";
        for (std::size_t k = 0; k < fields[f].values.size(); ++k)
          json << (k == 0 ? "" : ",") << exact(fields[f].values[k]);
        json << "]}";
      }
    json << ']';
  }

  // One file to read back and what it must hold.
  void
  write_case(std::ostream &json, const std::string &file, const Frame &frame, bool first)
  {
    json << (first ? "" : ",") << "\n  {\"file\": \"" << file << "\",\n   \"points\": [";
    for (std::size_t p = 0; p < frame.piece.points.size(); ++p)
      json << (p == 0 ? "" : ",") << '[' << exact(frame.piece.points[p][0]) << ','
           << exact(frame.piece.points[p][1]) << ',' << exact(frame.piece.points[p][2])
           << ']';
    json << "],\n   \"triangles\": [";
    for (std::size_t c = 0; c < frame.piece.triangles.size(); ++c)
      json << (c == 0 ? "" : ",") << '[' << frame.piece.triangles[c][0] << ','
           << frame.piece.triangles[c][1] << ',' << frame.piece.triangles[c][2] << ']';
    json << "],\n   \"point_fields\": ";
    write_fields(json, frame.data.point_fields);
    json << ",\n   \"cell_fields\": ";
    write_fields(json, frame.data.cell_fields);
    json << '}';
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

  if (argc != 2)
    {
      out << "usage: vtu_writer DIR\n";
      return 2;
    }
  const std::string directory = argv[1];
  if (this_rank == 0)
    {
      std::filesystem::create_directories(directory);
      out << "writing into " << directory << " on " << n_ranks << " rank(s)\n";
    }
  MPI_Barrier(env.communicator);

  // What tests/vtu_writer_read.py reads back: (file, its contents).
  std::vector<std::pair<std::string, Frame>> expected;
  if (n_ranks == 1)
    {
      // The 2 x 2 square, the 63 x 63 grid and an empty piece.
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
          expected.emplace_back(record, written);
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
      std::vector<Frame> frames;
      for (unsigned int r = 0; r < n_ranks; ++r)
        frames.push_back(frame_of(r));
      // The .pvtu with all pieces, then every piece on its own.
      expected.emplace_back(record, concatenated(frames));
      for (unsigned int r = 0; r < n_ranks; ++r)
        expected.emplace_back("pieces." + Utilities::int_to_string(r, 4) + ".vtu",
                              frames[r]);
    }
  if (this_rank == 0)
    {
      std::ofstream json(directory + "/expected.json");
      json << "{\"time\": " << exact(time) << ", \"ranks\": " << n_ranks
           << ", \"cases\": [";
      for (std::size_t c = 0; c < expected.size(); ++c)
        write_case(json, expected[c].first, expected[c].second, c == 0);
      json << "]}\n";
      check(out, static_cast<bool>(json), "expected.json written");
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
  out << total_checks - total_failures << " of " << total_checks << " checks passed on "
      << n_ranks << " rank(s)\n";
  return finish(out, total_failures == 0);
}
