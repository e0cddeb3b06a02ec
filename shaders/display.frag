#version 330 core
// Tone maps the film's mean into the RGBA8 display image, one fragment per image pixel (the target is
// an image-sized texture; ImageDisplay then copies it to the window at the layout's zoom and pan, and
// runs this only when the snapshot or a display setting changed). Pixels are fetched exactly
// (texelFetch), so the 8-bit values equal `penumbra render -o x.png`: the tone mapping below is
// core/image/tonemap.cpp's toSrgb8 — scale by 2^exposure, sRGB OETF, clamp, round to 1/255.
// app/ui/display_tonemap.cpp computes the same on the CPU (used on software GL such as llvmpipe).
uniform sampler2D uMean;    // RGB32F, row 0 = top image row (and row 0 of the target)
uniform sampler2D uStdErr;  // RGB32F standard error of the mean (1x1 when unavailable)
uniform float uExposure;    // stops
uniform int uTonemap;       // 0: sRGB OETF, 1: gamma 2.2
uniform int uView;          // 0: colour, 1: relative standard error, 2: NaN/Inf/negative highlight,
                            // 3: MIS light share (app/ui/light_share_map.h)
out vec4 fragColor;

bool bad(float v) { return isnan(v) || isinf(v); }

float oetf(float v) {
  if (uTonemap == 1) return pow(v, 1.0 / 2.2);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

// toSrgb8 for one channel, returned as the exact 8-bit level / 255.
float display(float linear) {
  if (bad(linear)) return 0.0;
  float t = linear * exp2(uExposure);
  if (isinf(t)) t = t > 0.0 ? 1.0 : 0.0;
  float v = clamp(oetf(max(t, 0.0)), 0.0, 1.0);
  return floor(v * 255.0 + 0.5) / 255.0;
}

// Blue → cyan → green → yellow → red.
vec3 ramp(float t) {
  t = clamp(t, 0.0, 1.0) * 4.0;
  if (t < 1.0) return vec3(0.0, t, 1.0);
  if (t < 2.0) return vec3(0.0, 1.0, 2.0 - t);
  if (t < 3.0) return vec3(t - 2.0, 1.0, 0.0);
  return vec3(1.0, 4.0 - t, 0.0);
}

// app/ui/light_share_map.h: share R / (R + G) of a light-share film, blue (0) → near-white (1/2) →
// red (1), dark grey where R + G is 0; colours as 8-bit levels.
vec3 lightShareColour(vec3 m) {
  float total = m.r + m.g;
  if (!(total > 0.0) || isinf(total)) return vec3(64.0) / 255.0;
  float s = clamp(m.r / total, 0.0, 1.0);
  vec3 a = s < 0.5 ? vec3(33.0, 102.0, 172.0) : vec3(247.0);
  vec3 b = s < 0.5 ? vec3(247.0) : vec3(178.0, 24.0, 43.0);
  float t = s < 0.5 ? 2.0 * s : 2.0 * s - 1.0;
  return floor(a + (b - a) * t + 0.5) / 255.0;
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec3 m = texelFetch(uMean, px, 0).rgb;
  if (uView == 3) {
    fragColor = vec4(lightShareColour(m), 1.0);
    return;
  }
  if (uView == 1) {
    // Relative standard error of the luminance, log scale: 0.1 % (blue) … 100 % (red); black: no data.
    ivec2 esize = textureSize(uStdErr, 0);
    vec3 e = texelFetch(uStdErr, min(px, esize - 1), 0).rgb;
    float lm = dot(m, vec3(0.2126, 0.7152, 0.0722));
    float le = dot(e, vec3(0.2126, 0.7152, 0.0722));
    if (esize != textureSize(uMean, 0) || !(lm > 0.0)) { fragColor = vec4(0.0, 0.0, 0.0, 1.0); return; }
    float r = le / lm;
    fragColor = vec4(ramp((log(max(r, 1e-3)) / log(10.0) + 3.0) / 3.0), 1.0);
    return;
  }
  vec3 c = vec3(display(m.r), display(m.g), display(m.b));
  if (uView == 2) {
    bool nonFinite = bad(m.r) || bad(m.g) || bad(m.b);
    bool negative = m.r < 0.0 || m.g < 0.0 || m.b < 0.0;
    if (nonFinite) c = vec3(1.0, 0.0, 1.0);
    else if (negative) c = vec3(0.0, 1.0, 1.0);
    else c = vec3(dot(c, vec3(0.2126, 0.7152, 0.0722)) * 0.6);
  }
  fragColor = vec4(c, 1.0);
}
