// PNG encoding of the plots' raster: signature, IHDR (8-bit RGB), one zlib-compressed
// IDAT with filter type 0 on every row, IEND.

#include "io/line_plot_detail.h"

#include <zlib.h>

#include <cstdint>
#include <stdexcept>

namespace clothsim::io::detail
{
  namespace
  {
    void
    append_u32(std::string &out, const std::uint32_t value)
    {
      for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<char>((value >> shift) & 0xFF));
    }

    // Chunk: length, type, data, CRC-32 of type and data.
    void
    append_chunk(std::string &png, const char *type, const std::string &data)
    {
      append_u32(png, static_cast<std::uint32_t>(data.size()));
      const std::size_t start = png.size();
      png.append(type, 4);
      png += data;
      append_u32(png,
                 crc32(0,
                       reinterpret_cast<const Bytef *>(png.data() + start),
                       static_cast<uInt>(png.size() - start)));
    }
  } // namespace


  std::string
  encode_png(const Image &image)
  {
    // Every row: filter type 0 (none), then RGB bytes.
    const std::size_t          row_bytes = 3 * static_cast<std::size_t>(image.width);
    std::vector<unsigned char> raw;
    raw.reserve((row_bytes + 1) * image.height);
    for (int y = 0; y < image.height; ++y)
      {
        raw.push_back(0);
        raw.insert(raw.end(),
                   image.pixels.begin() + y * row_bytes,
                   image.pixels.begin() + (y + 1) * row_bytes);
      }
    uLongf                     compressed_size = compressBound(raw.size());
    std::vector<unsigned char> compressed(compressed_size);
    if (compress2(compressed.data(), &compressed_size, raw.data(), raw.size(), 6) != Z_OK)
      throw std::runtime_error("write_line_plot: zlib compression failed");

    std::string header;
    append_u32(header, image.width);
    append_u32(header, image.height);
    header += std::string("\x08\x02\x00\x00\x00", 5); // 8 bit RGB, no interlace
    std::string png("\x89PNG\r\n\x1a\n", 8);
    append_chunk(png, "IHDR", header);
    append_chunk(png,
                 "IDAT",
                 std::string(reinterpret_cast<const char *>(compressed.data()),
                             compressed_size));
    append_chunk(png, "IEND", "");
    return png;
  }
} // namespace clothsim::io::detail
