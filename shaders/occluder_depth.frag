#version 450 core
// The occluder depth prepass: writes planar eye depth; a GL_MIN blend keeps the nearest surface and the
// starting (background) depth where it is nearer.
in float eyeDepth;

layout(location = 0) out float outEyeDepth;

void main() { outEyeDepth = eyeDepth; }
