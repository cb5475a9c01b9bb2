// VTK XML UnstructuredGrid files (version 1.0, UInt64 headers) for a triangle surface,
// written with the standard library and zlib only. Every DataArray is "binary": its bytes
// in the machine's byte order are cut into blocks of 32 KiB, each block is deflated, and
// the element holds base64 of the header (number of blocks, block size, size of the last
// block or 0 if it is full, compressed size of every block; all UInt64) followed by
// base64 of the compressed blocks -- the layout vtkZLibDataCompressor reads.

#include "io/vtu_writer.h"

#include "io/collective.h"
#include "io/output_file.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <limits>
#include <locale>
#include <stdexcept>

namespace clothsim::io
{
  namespace
  {
    // VTK's own block size for compressed arrays.
    constexpr std::size_t block_size = 32768;

    // VTK cell type of a 3-node triangle.
    constexpr std::uint8_t vtk_triangle = 5;

    // Binary data and headers are written as they lie in memory.
    const char *
    byte_order()
    {
      const std::uint16_t one = 1;
      unsigned char       first_byte;
      std::memcpy(&first_byte, &one, 1);
      return first_byte == 1 ? "LittleEndian" : "BigEndian";
    }

    const char *
    vtk_type_name(double)
    {
      return "Float64";
    }

    const char *
    vtk_type_name(std::int64_t)
    {
      return "Int64";
    }

    const char *
    vtk_type_name(std::uint8_t)
    {
      return "UInt8";
    }

    // Base64 (RFC 4648) with '=' padding.
    std::string
    base64(const unsigned char *data, const std::size_t size)
    {
      static const char table[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      std::string text;
      text.reserve(4 * ((size + 2) / 3));
      for (std::size_t i = 0; i < size; i += 3)
        {
          const std::uint32_t bits =
            (std::uint32_t(data[i]) << 16) |
            (i + 1 < size ? std::uint32_t(data[i + 1]) << 8 : 0) |
            (i + 2 < size ? std::uint32_t(data[i + 2]) : 0);
          text += table[(bits >> 18) & 63];
          text += table[(bits >> 12) & 63];
          text += i + 1 < size ? table[(bits >> 6) & 63] : '=';
          text += i + 2 < size ? table[bits & 63] : '=';
        }
      return text;
    }

    // The inline text of a compressed binary DataArray holding `values`.
    template <typename T>
    std::string
    compressed_base64(const std::vector<T> &values)
    {
      const auto       *raw      = reinterpret_cast<const unsigned char *>(values.data());
      const std::size_t size     = values.size() * sizeof(T);
      const std::size_t n_blocks = (size + block_size - 1) / block_size;

      std::vector<std::uint64_t> header = {n_blocks, block_size, size % block_size};
      std::vector<unsigned char> compressed;
      for (std::size_t b = 0; b < n_blocks; ++b)
        {
          const std::size_t begin             = b * block_size;
          const std::size_t length            = std::min(block_size, size - begin);
          const std::size_t offset            = compressed.size();
          uLongf            compressed_length = compressBound(length);
          compressed.resize(offset + compressed_length);
          if (compress2(compressed.data() + offset,
                        &compressed_length,
                        raw + begin,
                        length,
                        Z_BEST_SPEED) != Z_OK)
            throw std::runtime_error("zlib compression failed");
          compressed.resize(offset + compressed_length);
          header.push_back(compressed_length);
        }
      return base64(reinterpret_cast<const unsigned char *>(header.data()),
                    header.size() * sizeof(std::uint64_t)) +
             base64(compressed.data(), compressed.size());
    }

    // One DataArray element; no Name attribute if `name` is empty (the points).
    template <typename T>
    void
    write_array(std::ostream         &out,
                const std::string    &name,
                const unsigned int    n_components,
                const std::vector<T> &values)
    {
      out << "        <DataArray type=\"" << vtk_type_name(T()) << '"';
      if (!name.empty())
        out << " Name=\"" << name << '"';
      out << " NumberOfComponents=\"" << n_components << "\" format=\"binary\">\n"
          << compressed_base64(values) << "\n        </DataArray>\n";
    }

    // Throws if a field does not fit the piece or the piece's triangles its points.
    void
    check_piece(const std::string &path, const SurfacePiece &piece, const FrameData &data)
    {
      const auto fail = [&path](const std::string &message) {
        throw std::runtime_error("write_vtu_frame: " + path + ": " + message);
      };
      for (const auto &triangle : piece.triangles)
        for (const unsigned int vertex : triangle)
          if (vertex >= piece.points.size())
            fail("triangle vertex " + std::to_string(vertex) + " out of range (" +
                 std::to_string(piece.points.size()) + " points)");
      for (const bool point_data : {true, false})
        for (const Field &field : point_data ? data.point_fields : data.cell_fields)
          {
            const std::size_t n_entities =
              point_data ? piece.points.size() : piece.triangles.size();
            if (field.name.empty() ||
                field.name.find_first_of("<>&\"") != std::string::npos)
              fail("field name '" + field.name + "' is empty or needs XML escaping");
            if (field.n_components != 1 && field.n_components != 3)
              fail("field '" + field.name + "' has " +
                   std::to_string(field.n_components) + " components (1 or 3 allowed)");
            if (field.values.size() != field.n_components * n_entities)
              fail("field '" + field.name + "' has " +
                   std::to_string(field.values.size()) + " values, expected " +
                   std::to_string(field.n_components * n_entities));
          }
    }

    // The .vtu of one piece.
    void
    write_piece(std::ostream       &out,
                const SurfacePiece &piece,
                const FrameData    &data,
                const double        time)
    {
      std::vector<double> coordinates;
      coordinates.reserve(3 * piece.points.size());
      for (const auto &point : piece.points)
        coordinates.insert(coordinates.end(), point.begin(), point.end());
      std::vector<std::int64_t> connectivity, offsets;
      connectivity.reserve(3 * piece.triangles.size());
      offsets.reserve(piece.triangles.size());
      for (const auto &triangle : piece.triangles)
        {
          connectivity.insert(connectivity.end(), triangle.begin(), triangle.end());
          offsets.push_back(connectivity.size());
        }
      const std::vector<std::uint8_t> types(piece.triangles.size(), vtk_triangle);

      out.imbue(std::locale::classic());
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\""
          << byte_order() << "\" header_type=\"UInt64\""
          << " compressor=\"vtkZLibDataCompressor\">\n"
          << "  <UnstructuredGrid>\n"
          << "    <FieldData>\n"
          << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\""
          << " format=\"ascii\">"
          << std::setprecision(std::numeric_limits<double>::max_digits10) << time
          << "</DataArray>\n"
          << "    </FieldData>\n"
          << "    <Piece NumberOfPoints=\"" << piece.points.size()
          << "\" NumberOfCells=\"" << piece.triangles.size() << "\">\n"
          << "      <Points>\n";
      write_array(out, "", 3, coordinates);
      out << "      </Points>\n"
          << "      <Cells>\n";
      write_array(out, "connectivity", 1, connectivity);
      write_array(out, "offsets", 1, offsets);
      write_array(out, "types", 1, types);
      out << "      </Cells>\n";
      for (const bool point_data : {true, false})
        {
          const char *element = point_data ? "PointData" : "CellData";
          out << "      <" << element << ">\n";
          for (const Field &field : point_data ? data.point_fields : data.cell_fields)
            write_array(out, field.name, field.n_components, field.values);
          out << "      </" << element << ">\n";
        }
      out << "    </Piece>\n"
          << "  </UnstructuredGrid>\n"
          << "</VTKFile>\n";
    }

    std::string
    piece_name(const std::string &stem, const unsigned int rank)
    {
      return stem + "." + dealii::Utilities::int_to_string(rank, 4) + ".vtu";
    }

    // The .pvtu listing the pieces of all `n_ranks` ranks and the arrays they hold.
    void
    write_pvtu(std::ostream      &out,
               const std::string &stem,
               const unsigned int n_ranks,
               const FrameData   &data)
    {
      out << "<?xml version=\"1.0\"?>\n"
          << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\""
          << byte_order() << "\" header_type=\"UInt64\">\n"
          << "  <PUnstructuredGrid GhostLevel=\"0\">\n"
          << "    <PPoints>\n"
          << "      <PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n"
          << "    </PPoints>\n";
      for (const bool point_data : {true, false})
        {
          const char *element = point_data ? "PPointData" : "PCellData";
          out << "    <" << element << ">\n";
          for (const Field &field : point_data ? data.point_fields : data.cell_fields)
            out << "      <PDataArray type=\"Float64\" Name=\"" << field.name
                << "\" NumberOfComponents=\"" << field.n_components << "\"/>\n";
          out << "    </" << element << ">\n";
        }
      for (unsigned int r = 0; r < n_ranks; ++r)
        out << "    <Piece Source=\"" << piece_name(stem, r) << "\"/>\n";
      out << "  </PUnstructuredGrid>\n"
          << "</VTKFile>\n";
    }
  } // namespace


  std::string
  write_vtu_frame(const std::string  &directory,
                  const std::string  &stem,
                  const SurfacePiece &piece,
                  const FrameData    &data,
                  const double        time,
                  const MPI_Comm      communicator)
  {
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(communicator);
    const std::string  record  = stem + (n_ranks == 1 ? ".vtu" : ".pvtu");

    // Each file is written whole or not at all; an error on any rank reaches all.
    run_collectively(communicator, [&]() {
      const std::string path =
        directory + "/" + (n_ranks == 1 ? record : piece_name(stem, rank));
      check_piece(path, piece, data);
      write_file_atomically(path, [&](std::ostream &out) {
        write_piece(out, piece, data, time);
      });
      if (n_ranks > 1 && rank == 0)
        write_file_atomically(directory + "/" + record, [&](std::ostream &out) {
          write_pvtu(out, stem, n_ranks, data);
        });
    });
    return record;
  }
} // namespace clothsim::io
