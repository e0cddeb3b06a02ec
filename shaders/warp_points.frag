#version 330 core
in vec4 vColour;
out vec4 fragColor;
void main() { fragColor = vColour; }
