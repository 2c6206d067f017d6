#pragma once

#include <filesystem>

namespace spindrift {

/// Refuses, with an Error, a JPEG file (recognised by its start-of-image marker, whatever its extension)
/// whose Photoshop APP13 segment is shorter than the IPTC block it announces. OpenImageIO 2.4 reads that
/// block with the size the block claims, past the end of the segment's buffer (a heap over-read, found by
/// fuzz_background_image). Files that are not JPEG, and JPEG files without such a segment, pass.
void checkJpegIptcClaims(const std::filesystem::path& path);

}  // namespace spindrift
