#pragma once

#include <filesystem>

namespace spindrift {

/// Refuses, with an Error, a JPEG file (recognised by its start-of-image marker, whatever its extension) with
/// an application segment that OpenImageIO 2.4 reads past: a Photoshop APP13 segment shorter than the IPTC
/// block it announces, an Exif APP1 or ICC APP2 segment shorter than its own header, or an APP1, APP2 or
/// APP13 segment that ends inside the name OpenImageIO compares it with (heap over-reads, found by
/// fuzz_background_image). Files that are not JPEG pass.
void checkJpegMarkerClaims(const std::filesystem::path& path);

}  // namespace spindrift
