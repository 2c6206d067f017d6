#pragma once

#include <filesystem>

namespace spindrift {

/// Refuses, with an Error naming the chunk, a PNG file (recognised by its signature, whatever its extension)
/// with a chunk longer than the bytes left in the file. libpng allocates a chunk's claimed length before it
/// reads the chunk: a 110-byte file claiming a 3.6 GB chunk made it take 2 GB (found by
/// fuzz_background_image). Files that are not PNG pass.
void checkPngChunkClaims(const std::filesystem::path& path);

}  // namespace spindrift
