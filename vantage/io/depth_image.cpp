#include "vantage/io/depth_image.hpp"

#include <png.h>

#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "vantage/io/format_parsing.hpp"
#include "vantage/io/input_file.hpp"
#include "vantage/util/limits.hpp"
#include "vantage/util/memory.hpp"
#include "vantage/util/text.hpp"

namespace vantage {
namespace {

/// What libpng reads from, and where its error message goes.
struct PngSource {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  std::size_t pos = 0;
  char error[256] = {};
};

void read_bytes(png_structp png, png_bytep out, png_size_t n) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (n > source->size - source->pos) png_error(png, "the file ends inside the image");
  std::memcpy(out, source->data + source->pos, n);
  source->pos += n;
}

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
  auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(source->error, sizeof(source->error), "%s", message);
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

const char* colour_type_name(int type) {
  switch (type) {
    case PNG_COLOR_TYPE_GRAY:
      return "greyscale";
    case PNG_COLOR_TYPE_GRAY_ALPHA:
      return "greyscale with alpha";
    case PNG_COLOR_TYPE_RGB:
      return "RGB";
    case PNG_COLOR_TYPE_RGB_ALPHA:
      return "RGBA";
    case PNG_COLOR_TYPE_PALETTE:
      return "palette";
  }
  return "unknown colour type";
}

/// The header's problem for a depth image, or empty. Sets the image's size.
std::string check_header(png_structp png, png_infop info, DepthImage& image) {
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int depth = png_get_bit_depth(png, info);
  const int type = png_get_color_type(png, info);
  if (depth != 16 || type != PNG_COLOR_TYPE_GRAY) {
    return cat("has ", depth, "-bit ", colour_type_name(type),
               " pixels, not a depth image's 16-bit greyscale");
  }
  const auto pixels = static_cast<std::uint64_t>(width) * height;
  if (pixels > kMaxDepthImagePixels) {
    return cat("is ", width, " x ", height, " pixels, more than the ", kMaxDepthImagePixels,
               " a depth image may have");
  }
  const std::uint64_t available = available_memory();
  // NOTE: the depths and, later, a point of 3 doubles per pixel.
  const double bytes = static_cast<double>(pixels) * (2.0 + 24.0);
  if (available > 0 && bytes > static_cast<double>(available)) {
    return cat("is ", width, " x ", height, " pixels, which need about ", describe_bytes(bytes),
               ", more than the ", describe_bytes(static_cast<double>(available)),
               " this machine has available");
  }
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  return {};
}

/// libpng's part: nothing here owns memory, so its longjmp skips no destructor. Returns false
/// with `source.error` or `problem` set.
bool decode(png_structp png, png_infop info, PngSource& source, DepthImage& image,
            std::vector<png_bytep>& rows, std::string& problem) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_read_fn(png, &source, &read_bytes);
  png_set_sig_bytes(png, 0);
  png_read_info(png, info);
  problem = check_header(png, info, image);
  if (!problem.empty()) return false;
  image.depth.resize(static_cast<std::size_t>(image.width) * image.height);
  rows.resize(static_cast<std::size_t>(image.height));
  for (int v = 0; v < image.height; ++v) {
    rows[static_cast<std::size_t>(v)] =
        reinterpret_cast<png_bytep>(image.depth.data() + static_cast<std::size_t>(v) * image.width);
  }
  if constexpr (std::endian::native == std::endian::little) png_set_swap(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

void DepthEncoding::validate() const {
  if (!(std::isfinite(units_per_metre) && units_per_metre > 0.0)) {
    throw std::invalid_argument(
        cat("depth.scale must be a positive number of units a metre, got ", units_per_metre));
  }
}

DepthImage decode_depth_png(std::string_view bytes) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0) {
    throw FormatError("not a PNG image (the first 8 bytes are not PNG's signature)");
  }
  PngSource source{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, &on_error, &on_warning);
  if (png == nullptr) throw FormatError("libpng could not start");
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw FormatError("libpng could not start");
  }
  // NOTE: libpng's own cap on a row's size and on chunks' memory, under ours.
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_set_chunk_malloc_max(png, 8u << 20);
  DepthImage image;
  std::vector<png_bytep> rows;
  std::string problem;
  const bool ok = decode(png, info, source, image, rows, problem);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!ok) {
    throw FormatError(problem.empty() ? cat("a broken PNG: ", source.error) : problem);
  }
  return image;
}

DepthImage read_depth_png(const std::filesystem::path& path) {
  try {
    return decode_depth_png(read_input_file(path, InputKind::kDepthImage));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(cat(path.string(), ": ", e.what()));
  }
}

DepthFrame depth_frame(const DepthImage& image, const PinholeIntrinsics& k,
                       const DepthEncoding& encoding) {
  k.validate();
  encoding.validate();
  if (image.width != k.width || image.height != k.height) {
    throw std::invalid_argument(cat("the depth image is ", image.width, " x ", image.height,
                                    " pixels, the intrinsics' ", k.width, " x ", k.height));
  }
  return {.width = image.width,
          .height = image.height,
          .depth = image.depth,
          .fx = k.fx,
          .fy = k.fy,
          .cx = k.cx,
          .cy = k.cy,
          .units_per_metre = encoding.units_per_metre,
          .invalid = encoding.invalid};
}

PointCloud depth_to_points(const DepthImage& image, const PinholeIntrinsics& k,
                           const DepthEncoding& encoding) {
  const DepthFrame frame = depth_frame(image, k, encoding);
  PointCloud points;
  points.reserve(image.depth.size());
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const std::uint16_t d = image.depth[static_cast<std::size_t>(v) * image.width + u];
      if (d != encoding.invalid) points.push_back(frame.optical_point(u, v, d));
    }
  }
  return points;
}

}  // namespace vantage
