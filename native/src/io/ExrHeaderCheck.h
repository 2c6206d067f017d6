#pragma once

#include <filesystem>

namespace spindrift {

/// Refuses, with an Error naming the claim, an OpenEXR file (recognised by its magic number, whatever its
/// extension) whose header claims more than the file can hold: an attribute longer than the bytes left, a
/// preview image larger than its attribute, or more chunks than the file has room for their offsets. OpenEXR
/// 3.1 allocates, and for strings zero-fills, whatever a header claims before it finds the file too short:
/// an 893-byte file can make it take 2 GB (found by fuzz_background_image). Files that are not OpenEXR pass.
void checkExrHeaderClaims(const std::filesystem::path& path);

}  // namespace spindrift
