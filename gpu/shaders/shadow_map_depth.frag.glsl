#version 450 core
// Depth only: the framebuffer has no colour attachment; depth comes from rasterisation
// (plus the glPolygonOffset slope term).
void main() {}
