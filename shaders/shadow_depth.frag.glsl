#version 330 core
// Depth pass of the shadow-mapped baseline: depth only (no colour attachment).

void main() {}
