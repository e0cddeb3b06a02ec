// One function per ImGui panel (scene, integrator, sampler, camera, display, stats, help), each in its
// own file. They read and edit the ViewerController; nothing here touches GL.
#pragma once

#include <string>

#include "app/ui/convergence_tracker.h"
#include "app/ui/overwrite_guard.h"
#include "app/ui/viewer_controller.h"

namespace penumbra::ui {

// UI-only state shared by the panels (text fields, messages, toggles).
struct PanelState {
  char openPath[1024] = "";
  char savePath[1024] = "penumbra.png";
  char sceneSavePath[1024] = "scene-live.xml";
  bool showHelp = false;
  bool hoverValid = false;  // pixel inspector: the cursor is over the image
  int hoverX = 0, hoverY = 0;
  bool requestSavePng = false;
  OverwriteGuard imageSaveGuard, sceneSaveGuard;  // Save and Save as ask again before replacing a file
  double frameMs = 0;                             // time the last UI frame took to draw and present
  float layoutZoom = 1.f;                         // the zoom the image was last drawn at (fit computes it)
  // Convergence panel: live RMSE against time for each accumulation since the scene or camera changed.
  ConvergenceTracker convergence;
  char referencePath[1024] = "";
  bool convergenceNoLight = false;
};

void drawScenePanel(ViewerController& c, PanelState& st);
void drawIntegratorPanel(ViewerController& c, PanelState& st);
void drawSamplerPanel(ViewerController& c, PanelState& st);
void drawCameraPanel(ViewerController& c, PanelState& st);
void drawMaterialsPanel(ViewerController& c, PanelState& st);  // only for scenes with glossy BSDFs
void drawDisplayPanel(ViewerController& c, PanelState& st);
void drawStatsPanel(ViewerController& c, PanelState& st);
void drawConvergencePanel(ViewerController& c, PanelState& st);
void drawHelpPanel(ViewerController& c, PanelState& st);

}  // namespace penumbra::ui
