// Writes the liquid particles of one frame of a scene file as a binary little-endian PLY (x, y, z, radius in
// world space). The benchmark needs them in Python, for VTK's fluid mapper and for the resampled scaling
// scenes, and Debian's Python has no reader for OpenVDB point grids; this reads them with Spindrift's own
// loader, so both renderers see exactly the same particles.
//
//   spindrift_export_particles scene.json frame out.ply
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "spindrift/Particles.h"
#include "spindrift/Scene.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s scene.json frame out.ply\n", argv[0]);
    return 2;
  }
  try {
    const spindrift::Scene scene = spindrift::loadScene(argv[1]);
    const spindrift::Particles particles = spindrift::loadParticles(scene, std::stoi(argv[2]));
    std::vector<float> rows;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (particles.kinds[i] != spindrift::ParticleKind::Liquid) continue;
      const auto& p = particles.positions[i];
      rows.insert(rows.end(), {p.x, p.y, p.z, particles.radii[i]});
    }
    std::ofstream out(argv[3], std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << rows.size() / 4
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radius\nend_header\n";
    out.write(reinterpret_cast<const char*>(rows.data()),
              static_cast<std::streamsize>(rows.size() * sizeof(float)));
    if (!out) throw std::runtime_error(std::string("cannot write ") + argv[3]);
    std::printf("%zu liquid particles\n", rows.size() / 4);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "spindrift_export_particles: %s\n", error.what());
    return 1;
  }
  return 0;
}
