#version 450 core
// Vertices 0-2: one triangle that covers the viewport. Vertices 3-8 of instance i: the two triangles of pixel
// tile i (framedata/PixelTiles.h), row by row, or nothing where drawnTiles does not mark the tile, so a pass
// shades only the tiles that hold liquid (drawFullscreen). Fragment shaders read gl_FragCoord; no varyings,
// so a pixel's value does not depend on which of the two draws shades it.
#include "lib/frame.glsl"

layout(binding = 15) uniform usampler2D drawnTiles;  // kPixelTilesTextureUnit

void main() {
  if (gl_VertexID < 3) {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  int tilesAcross = textureSize(drawnTiles, 0).x;
  ivec2 tile = ivec2(gl_InstanceID % tilesAcross, gl_InstanceID / tilesAcross);
  if (texelFetch(drawnTiles, tile, 0).r == 0u) {
    gl_Position = vec4(2.0, 2.0, 0.0, 1.0);  // every vertex of the tile here: no area, nothing drawn
    return;
  }
  // Corners (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1): the shared diagonal is drawn once (the fill rule).
  int corner = gl_VertexID - 3;
  ivec2 offset = ivec2(corner == 1 || corner == 2 || corner == 4 ? 1 : 0, corner == 2 || corner >= 4 ? 1 : 0);
  float tileSize = frame.pixelTiles.x;
  vec2 pixel = min((vec2(tile) + vec2(offset)) * tileSize, frame.viewportSize.xy);
  gl_Position = vec4(pixel * frame.viewportSize.zw * 2.0 - 1.0, 0.0, 1.0);
}
