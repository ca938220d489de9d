// Image files through OpenImageIO. EXR: linear float RGB radiance, no tonemap. PNG: exposure,
// filmic tonemap and sRGB (shaders/shared/tonemap.h, the same curve as the GPU tonemap pass).
// Writes are atomic (temporary file + rename): a failed write leaves nothing half-written.
#pragma once

#include <filesystem>

#include "runtime/image/image.h"

namespace lantern::runtime {

enum class ImageFormat { Exr, Png };

// The format implied by a path's extension (.exr or .png); InputError otherwise.
ImageFormat image_format_for(const std::filesystem::path& path);

// Writes by extension. Refuses (RuntimeError) an image holding NaN or Inf: the renderer must
// never produce one, and a file that hides it would be worse than a failed run.
void write_image(const std::filesystem::path& path, const ImageRGBA32F& image,
                 float exposure = 1.0f);
void write_exr(const std::filesystem::path& path, const ImageRGBA32F& image);
void write_png(const std::filesystem::path& path, const ImageRGBA32F& image, float exposure);

// Reads any format OpenImageIO knows into RGBA float (missing channels: G=B=R for grey, A=1).
// Values are the file's own (an 8-bit PNG reads back as its encoded values in [0,1]).
ImageRGBA32F read_image(const std::filesystem::path& path);

}  // namespace lantern::runtime
