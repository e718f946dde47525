// Reading a figure's PNG (8-bit RGB or RGBA, not interlaced: what gnuplot's
// pngcairo writes) into pixels, to measure what a test's figure shows.
// Needs zlib (TOWSIM_TEST_HAVE_ZLIB); without it load_png says so.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#ifdef TOWSIM_TEST_HAVE_ZLIB
#include <zlib.h>
#endif

namespace towsim::testing {

/// An image's pixels, row by row from the top: red, green, blue (0 .. 255).
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  int channel(int x, int y, int c) const {
    return rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) +
               static_cast<std::size_t>(c)];
  }
  /// Grey level, 0 black .. 255 white.
  int at(int x, int y) const { return (channel(x, y, 0) + channel(x, y, 1) + channel(x, y, 2)) / 3; }
  bool dark(int x, int y, int below = 128) const { return at(x, y) < below; }
};

/// Load `path` into `img`; false with `error` set when it cannot.
inline bool load_png(const std::string& path, Image& img, std::string& error) {
#ifndef TOWSIM_TEST_HAVE_ZLIB
  (void)path, (void)img;
  error = "built without zlib";
  return false;
#else
  std::ifstream in(path, std::ios::binary);
  const std::string d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (d.size() < 8 || d.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
    error = path + ": not a PNG";
    return false;
  }
  auto u32 = [&d](std::size_t i) {
    return (static_cast<std::uint32_t>(static_cast<unsigned char>(d[i])) << 24) |
           (static_cast<std::uint32_t>(static_cast<unsigned char>(d[i + 1])) << 16) |
           (static_cast<std::uint32_t>(static_cast<unsigned char>(d[i + 2])) << 8) |
           static_cast<std::uint32_t>(static_cast<unsigned char>(d[i + 3]));
  };
  std::string idat;
  int bpp = 0;
  for (std::size_t i = 8; i + 12 <= d.size();) {
    const std::uint32_t n = u32(i);
    const std::string type = d.substr(i + 4, 4);
    if (type == "IHDR") {
      img.width = static_cast<int>(u32(i + 8));
      img.height = static_cast<int>(u32(i + 12));
      const int depth = static_cast<unsigned char>(d[i + 16]), colour = static_cast<unsigned char>(d[i + 17]);
      const int interlace = static_cast<unsigned char>(d[i + 20]);
      bpp = colour == 2 ? 3 : colour == 6 ? 4 : 0;
      if (depth != 8 || bpp == 0 || interlace != 0) {
        error = path + ": not an 8-bit RGB(A) PNG without interlacing";
        return false;
      }
    } else if (type == "IDAT") {
      idat += d.substr(i + 8, n);
    }
    i += 12 + n;
  }
  const std::size_t stride = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(bpp);
  std::vector<unsigned char> raw((stride + 1) * static_cast<std::size_t>(img.height));
  uLongf size = raw.size();
  if (bpp == 0 || uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(idat.data()), idat.size()) != Z_OK ||
      size != raw.size()) {
    error = path + ": cannot inflate its image data";
    return false;
  }
  // Undo the row filters (PNG specification, section 9).
  std::vector<unsigned char> prev(stride, 0), line(stride);
  img.rgb.assign(3 * static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height), 0);
  for (int y = 0; y < img.height; ++y) {
    const unsigned char* r = &raw[static_cast<std::size_t>(y) * (stride + 1)];
    const int filter = r[0];
    for (std::size_t x = 0; x < stride; ++x) {
      const int a = x >= static_cast<std::size_t>(bpp) ? line[x - bpp] : 0, b = prev[x];
      const int c = x >= static_cast<std::size_t>(bpp) ? prev[x - bpp] : 0;
      int p = 0;
      if (filter == 1) p = a;
      if (filter == 2) p = b;
      if (filter == 3) p = (a + b) / 2;
      if (filter == 4) {
        const int e = a + b - c, pa = std::abs(e - a), pb = std::abs(e - b), pc = std::abs(e - c);
        p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      line[x] = static_cast<unsigned char>(r[1 + x] + p);
    }
    for (int x = 0; x < img.width; ++x) {
      const std::size_t o = static_cast<std::size_t>(x) * static_cast<std::size_t>(bpp);
      for (std::size_t c = 0; c < 3; ++c)
        img.rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x)) +
                c] = line[o + c];
    }
    prev = line;
  }
  return true;
#endif
}

}  // namespace towsim::testing
