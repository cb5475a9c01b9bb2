#pragma once

// A small VTK XML writer for a connected triangle surface (no VTK library needed): every
// vertex is written once, triangles refer to it by index, and per-triangle fields are
// true cell data. Files are VTK XML UnstructuredGrid version 1.0, every array
// zlib-compressed and base64-encoded inline ("binary"), as ParaView and VTK's XML readers
// expect them.

#include <mpi.h>

#include <array>
#include <string>
#include <vector>

namespace clothsim::io
{
  // One rank's part of a triangulated surface: its triangles and the vertices they use.
  struct SurfacePiece
  {
    std::vector<std::array<double, 3>>       points;    // reference positions, m
    std::vector<std::array<unsigned int, 3>> triangles; // indices into points
  };

  // A named field on the piece: `n_components` values per point (point data) or per
  // triangle (cell data).
  struct Field
  {
    std::string         name;
    unsigned int        n_components; // 1 (scalar) or 3 (vector)
    std::vector<double> values; // point- or triangle-major: values[n_components * i + c]
  };

  // The fields of one frame. Every rank lists the same fields in the same order.
  struct FrameData
  {
    std::vector<Field> point_fields;
    std::vector<Field> cell_fields;
  };

  // Writes one frame: with one MPI rank `directory/stem.vtu`; with several, every rank
  // writes `directory/stem.RRRR.vtu` (RRRR = rank, 4 digits) and rank 0 writes
  // `directory/stem.pvtu` listing the pieces and the arrays. `time` (s) goes into every
  // .vtu as FieldData "TIME" (as deal.II does, so that ParaView shows the time). Returns
  // the name of the record to list in the .pvd (stem.vtu or stem.pvtu, without
  // directory). Each file is written whole or not at all (io/output_file.h). Collective
  // over `communicator`: if any rank cannot write its file (io::OutputError), or its
  // piece and fields do not fit together (a field of the wrong size, n_components not 1
  // or 3, a vertex index out of range, a name with one of <>&"; std::runtime_error),
  // every rank throws, naming the path on the rank that failed.
  std::string
  write_vtu_frame(const std::string  &directory,
                  const std::string  &stem,
                  const SurfacePiece &piece,
                  const FrameData    &data,
                  const double        time,
                  const MPI_Comm      communicator);
} // namespace clothsim::io
