#include "app/cli/false_colour.h"

namespace penumbra::cli {

Rgb falseColour(double t) {
  static const double k[][3] = {{0.0, 0.0, 0.02},   {0.23, 0.06, 0.44}, {0.55, 0.16, 0.51},
                                {0.87, 0.29, 0.41}, {0.99, 0.62, 0.42}, {0.99, 0.99, 0.75}};
  // Written so that NaN fails the first test (std::clamp passes NaN through, and int(NaN) is undefined).
  if (!(t > 0)) t = 0;
  if (!(t < 1)) t = 1;
  t *= 5;
  const int i = t >= 4 ? 4 : int(t);
  const double f = t - i;
  return {k[i][0] + f * (k[i + 1][0] - k[i][0]), k[i][1] + f * (k[i + 1][1] - k[i][1]),
          k[i][2] + f * (k[i + 1][2] - k[i][2])};
}

}  // namespace penumbra::cli
