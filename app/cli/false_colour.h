// The "magma"-like false-colour ramp of the error maps in equal-time.png (penumbra converge).
#pragma once

namespace penumbra::cli {

struct Rgb {
  double r = 0, g = 0, b = 0;  // each in [0, 1]
};

// t = 0 is near black, t = 1 pale yellow. Defined for every double: t below 0 and NaN give the colour
// of 0, t above 1 (and +infinity) that of 1.
Rgb falseColour(double t);

}  // namespace penumbra::cli
