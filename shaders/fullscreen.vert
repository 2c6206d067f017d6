#version 450 core
// Vertices 0-2: one triangle that covers the viewport. Vertex 3 + i: pixel tile i (framedata/PixelTiles.h),
// row by row, as one point the tile's size, or nothing where drawnTiles does not mark the tile, so a pass
// shades only the tiles that hold liquid (drawFullscreen). A point is a square llvmpipe rasterises whole:
// a tile drawn as two triangles had the 4 x 4 blocks along their shared diagonal shaded twice, once for each
// (the smoothing 41-44 against 34-35 ms, the refraction 45-52 against 39-41 ms on the dam break). Fragment
// shaders read gl_FragCoord; no varyings, so a pixel's value does not depend on which draw shades it.
#include "lib/frame.glsl"

layout(binding = 15) uniform usampler2D drawnTiles;  // kPixelTilesTextureUnit

void main() {
  if (gl_VertexID < 3) {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  // Vertex 3 + i: pixel tile i as one point the tile's size, centred on it (drawn as GL_POINTS).
  int tilesAcross = textureSize(drawnTiles, 0).x;
  int index = gl_VertexID - 3;
  ivec2 tile = ivec2(index % tilesAcross, index / tilesAcross);
  float tileSize = frame.pixelTiles.x;
  gl_PointSize = tileSize;
  if (texelFetch(drawnTiles, tile, 0).r == 0u) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume: not drawn
    return;
  }
  // In the viewport drawFullscreen widens to whole tiles, so that every tile's centre lies inside it.
  vec2 centre = (vec2(tile) + 0.5) / vec2(textureSize(drawnTiles, 0));
  gl_Position = vec4(centre * 2.0 - 1.0, 0.0, 1.0);
}
