// The ray-marched surface's uniform grid and its density (adaptive ray marching paper, 4.1 and equation 2).
// Cells of side cellSize >= h, numbered x fastest; `sortedParticles` holds each cell's particles contiguously
// from cellStart[c], cellCount[c] of them (built by raymarch_grid.comp).
uniform vec3 gridOrigin;
uniform float cellSize;
uniform ivec3 gridSize;
uniform float smoothingRadius;  // h, the largest particle support

layout(std430, binding = 1) buffer CellCounts { uint cellCount[]; };
layout(std430, binding = 2) buffer CellStarts { uint cellStart[]; };
layout(std430, binding = 4) buffer SortedParticles { vec4 sortedParticles[]; };

int cellIndex(ivec3 cell) { return (cell.z * gridSize.y + cell.y) * gridSize.x + cell.x; }
bool insideGrid(ivec3 cell) { return all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, gridSize)); }
ivec3 cellOf(vec3 position) { return ivec3(floor((position - gridOrigin) / cellSize)); }

// The density divided by one particle's peak m W(0, h): sum over particles j within their support h_j of
// P(q) = (1 - q^2)^3, q = |x - x_j| / h_j (equation 7's spline with the normalisation divided out; h_j is the
// particle's w, at most smoothingRadius). `gradient` receives its gradient, -6 (1 - q^2)^2 (x - x_j) / h_j^2
// summed (equation 11 before normalising).
float densityAt(vec3 position, out vec3 gradient) {
  gradient = vec3(0.0);
  float density = 0.0;
  ivec3 centre = cellOf(position);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 cell = centre + ivec3(dx, dy, dz);
        if (!insideGrid(cell)) continue;
        int index = cellIndex(cell);
        uint begin = cellStart[index];
        uint end = begin + cellCount[index];
        for (uint j = begin; j < end; ++j) {
          vec4 particle = sortedParticles[j];
          vec3 offset = position - particle.xyz;
          float inverseSquaredSupport = 1.0 / (particle.w * particle.w);
          float q2 = dot(offset, offset) * inverseSquaredSupport;
          if (q2 >= 1.0) continue;
          float falloff = 1.0 - q2;
          density += falloff * falloff * falloff;
          gradient -= 6.0 * falloff * falloff * inverseSquaredSupport * offset;
        }
      }
  return density;
}
