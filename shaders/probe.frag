#version 450
// Minimal loop: one constant colour.
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(0.4, 0.5, 0.3, 1.0); }
