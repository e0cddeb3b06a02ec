// How the viewer shows the image: exposure, tone curve, false colour, zoom and pan, the compare
// divider. Display-only state: changing it never restarts the engine.
#pragma once

namespace penumbra::ui {

enum class Tonemap : int { Srgb = 0, Gamma22 = 1 };
// The user's false-colour choices (Display panel), and MisLightShare: how a light-share film
// (ViewerController::setLightShareView) is shown, never chosen directly.
enum class FalseColour : int { None = 0, RelativeError = 1, BadPixels = 2, MisLightShare = 3 };

struct DisplaySettings {
  float exposure = 0.f;  // stops
  Tonemap tonemap = Tonemap::Srgb;
  FalseColour falseColour = FalseColour::None;
  float zoom = 1.f;              // screen pixels per image pixel
  float panX = 0.f, panY = 0.f;  // image offset from the centred position, screen pixels
  bool fit = true;               // zoom follows the image area until the user zooms
  float compareDivider = 0.5f;   // compare mode: divider position as a fraction of the image width
};

}  // namespace penumbra::ui
