// Writes the liquid particles of one frame of a scene file as a binary little-endian PLY (x, y, z, radius in
// world space), or with `whitewater` its foam particles (spray, surface foam and bubbles, with their type as
// Spindrift's PLY reader reads it: 2 spray, 4 bubble, 8 foam). The benchmark needs them in Python, for VTK's
// fluid mapper, the resampled scaling scenes and the Cycles references' whitewater, and Debian's Python has
// no reader for OpenVDB point grids; this reads them with Spindrift's own loader, so every renderer sees
// exactly the same particles.
//
//   spindrift_export_particles scene.json frame out.ply [liquid|whitewater]
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
  const std::string what = argc == 5 ? argv[4] : "liquid";
  if ((argc != 4 && argc != 5) || (what != "liquid" && what != "whitewater")) {
    std::fprintf(stderr, "usage: %s scene.json frame out.ply [liquid|whitewater]\n", argv[0]);
    return 2;
  }
  using spindrift::ParticleKind;
  const bool whitewater = what == "whitewater";
  try {
    const spindrift::Scene scene = spindrift::loadScene(argv[1]);
    const spindrift::Particles particles = spindrift::loadParticles(scene, std::stoi(argv[2]));
    // Each row: x, y, z, radius and, for whitewater, the type (a float holding 2, 4 or 8).
    const std::size_t columns = whitewater ? 5 : 4;
    std::vector<float> rows;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const ParticleKind kind = particles.kinds[i];
      if ((kind == ParticleKind::Liquid) == whitewater) continue;
      const auto& p = particles.positions[i];
      rows.insert(rows.end(), {p.x, p.y, p.z, particles.radii[i]});
      if (whitewater)
        rows.push_back(kind == ParticleKind::Spray ? 2.0f : kind == ParticleKind::Bubble ? 4.0f : 8.0f);
    }
    std::ofstream out(argv[3], std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << rows.size() / columns
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radius\n"
        << (whitewater ? "property float type\n" : "") << "end_header\n";
    out.write(reinterpret_cast<const char*>(rows.data()),
              static_cast<std::streamsize>(rows.size() * sizeof(float)));
    if (!out) throw std::runtime_error(std::string("cannot write ") + argv[3]);
    std::printf("%zu %s particles\n", rows.size() / columns, what.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "spindrift_export_particles: %s\n", error.what());
    return 1;
  }
  return 0;
}
