#version 330 core
// Warp inspector: warped points (coloured by sample index) and lines (one colour) in 3-D.
layout(location = 0) in vec4 aPoint;  // xyz: position; w: sample index / (count - 1), < 0 for lines
uniform mat4 uMvp;
uniform float uPointSize;
uniform vec4 uColour;                 // for w < 0
out vec4 vColour;

// Blue -> cyan -> green -> yellow -> red (as display.frag's false colour).
vec3 ramp(float t) {
  t = clamp(t, 0.0, 1.0) * 4.0;
  if (t < 1.0) return vec3(0.0, t, 1.0);
  if (t < 2.0) return vec3(0.0, 1.0, 2.0 - t);
  if (t < 3.0) return vec3(t - 2.0, 1.0, 0.0);
  return vec3(1.0, 4.0 - t, 0.0);
}

void main() {
  gl_Position = uMvp * vec4(aPoint.xyz, 1.0);
  gl_PointSize = uPointSize;
  vColour = aPoint.w < 0.0 ? uColour : vec4(ramp(aPoint.w), 1.0);
}
