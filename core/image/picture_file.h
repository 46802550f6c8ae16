// Picture files chosen by their extension: PNG (8-bit sRGB, tone-mapped)
// or a linear format that keeps radiance as it is (PFM, OpenEXR, Radiance
// HDR). One place decides what `--out x.ext` means for every command.
#pragma once

#include <optional>
#include <string>

#include "image/image.h"

namespace bounce {

enum class picture_format { png, pfm, exr, hdr };

// The format an extension names (case-insensitive), or nullopt.
std::optional<picture_format> picture_format_of(const std::string& path);

// Whether the format stores linear radiance (everything but PNG).
bool is_linear(picture_format format);

// "png, pfm, exr or hdr": for messages.
const char* picture_extensions();

// Checked before any long work starts: an error naming `option` and the
// problem (unknown extension, missing folder, a folder in the way, a folder
// that cannot be written), or an empty string. `picture`: the extension must
// name a picture format.
std::string check_output_path(const std::string& option, const std::string& path, bool picture);

// Writes `img` (linear radiance) in the format of the path's extension:
// PNG as radiance x exposure through the sRGB curve, the linear formats
// unscaled. Returns false with `error` naming the file.
bool write_picture(const std::string& path, const image& img, double exposure, std::string& error);

// The linear formats, one each.
bool write_exr(const std::string& path, const image& img, std::string& error);
bool write_hdr(const std::string& path, const image& img, std::string& error);

}  // namespace bounce
