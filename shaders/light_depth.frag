#version 460
// light_depth.frag - depth only: nothing to shade.
void main() {}
