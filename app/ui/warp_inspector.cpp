#include "app/ui/warp_inspector.h"
#include "app/ui/panel_text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/quaternion.hpp>

#include "app/platform/platform.h"
#include "app/ui/gl_program.h"
#include "core/image/image_io.h"
#include "core/image/tonemap.h"
#include "core/math/error.h"
#include "core/sampling/sampler_table.h"
#include "penumbra_shaders.h"  // generated from shaders/

namespace penumbra::ui {

namespace {

const char* const kPanelNames[3] = {"histogram", "density", "difference"};

ImTextureID texId(GLuint tex) {
  return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(tex));
}

// Points of the view as vec4 (xyz, t): t = index / (n - 1) for samples, -1 for lines.
void uploadVec4(GLuint vao, GLuint vbo, const std::vector<float>& data) {
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void pushLine(std::vector<float>& v, glm::vec3 a, glm::vec3 b) {
  for (glm::vec3 p : {a, b}) v.insert(v.end(), {p.x, p.y, p.z, -1.f});
}

void pushCircle(std::vector<float>& v, int axis, float z, float radius, int segments) {
  auto at = [&](int i) {
    float a = 2.f * kPi * i / segments;
    glm::vec3 p(radius * std::cos(a), radius * std::sin(a), z);
    if (axis == 0) return glm::vec3(p.z, p.x, p.y);  // circle in the yz plane
    if (axis == 1) return glm::vec3(p.x, p.z, p.y);  // circle in the xz plane
    return p;                                        // circle in the xy plane
  };
  for (int i = 0; i < segments; ++i) pushLine(v, at(i), at(i + 1));
}

const char* paramLabel(WarpType t) {
  return t == WarpType::UniformCone ? "cos(theta_max)" : "alpha";
}

void colourBar(ImDrawList* dl, ImVec2 p0, ImVec2 p1, bool diverging) {
  const int n = 64;
  float w = (p1.x - p0.x) / n;
  for (int i = 0; i < n; ++i) {
    double t = (i + 0.5) / n;
    std::array<uint8_t, 3> c = diverging ? divergingColour(2.0 * t - 1.0) : sequentialColour(t);
    dl->AddRectFilled(ImVec2(p0.x + i * w, p0.y), ImVec2(p0.x + (i + 1) * w + 0.5f, p1.y),
                      IM_COL32(c[0], c[1], c[2], 255));
  }
  dl->AddRect(p0, p1, IM_COL32(120, 120, 120, 255));
}

}  // namespace

WarpInspector::WarpInspector(const WarpInspectorSettings& initial) : settings_(initial) {
  program_ = linkProgram(shaders::k_warp_points_vert, shaders::k_warp_points_frag, "warp_points");
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenVertexArrays(1, &refVao_);
  glGenBuffers(1, &refVbo_);
  glGenTextures(3, panelTex_);
  for (GLuint t : panelTex_) {
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const uint8_t black[4] = {0, 0, 0, 255};
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, black);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  worker_.request(settings_);
}

WarpInspector::~WarpInspector() {
  glDeleteTextures(3, panelTex_);
  if (fbo_) {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &colour_);
    glDeleteRenderbuffers(1, &depth_);
  }
  glDeleteBuffers(1, &vbo_);
  glDeleteBuffers(1, &refVbo_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteVertexArrays(1, &refVao_);
  glDeleteProgram(program_);
}

bool WarpInspector::upToDate() const {
  return shownPoints_ && shownVerdict_ && shownPoints_->settings == settings_ &&
         shownVerdict_->settings == settings_;
}

void WarpInspector::resetView() {
  viewSpherical_ = showsSphere(settings_);
  if (viewSpherical_) {
    // Looking at the sphere from above the equator, +z up on the screen.
    rot_ = glm::angleAxis(glm::radians(-62.f), glm::vec3(1, 0, 0)) *
           glm::angleAxis(glm::radians(-30.f), glm::vec3(0, 0, 1));
    distance_ = 4.2f;
  } else {
    rot_ = glm::quat(1.f, 0.f, 0.f, 0.f);  // the plane seen from +z
    distance_ = 4.0f;
  }
  viewInit_ = true;
  sceneDirty_ = true;
}

void WarpInspector::uploadPoints() {
  const WarpPoints& p = *shownPoints_;
  std::vector<float> data;
  data.reserve((p.points.size() + p.lines.size()) * 4);
  const float denom = p.points.size() > 1 ? float(p.points.size() - 1) : 1.f;
  for (size_t i = 0; i < p.points.size(); ++i) {
    const Vec3& v = p.points[i];
    data.insert(data.end(), {v.x, v.y, v.z, float(i) / denom});
  }
  for (const Vec3& v : p.lines) data.insert(data.end(), {v.x, v.y, v.z, -1.f});
  uploadVec4(vao_, vbo_, data);
  pointCount_ = p.points.size();
  lineVertexCount_ = p.lines.size();
  sceneDirty_ = true;

  // Reference geometry of the domain.
  if (!refValid_ || refKey_ != inspectedName(p.settings)) {
    std::vector<float> ref;
    refSpherical_ = showsSphere(p.settings);
    if (refSpherical_) {
      for (int axis = 0; axis < 3; ++axis) pushCircle(ref, axis, 0.f, 1.f, 128);
      if (p.settings.bsdf) {  // the normal and the incident direction wo, drawn past the sphere
        pushLine(ref, glm::vec3(0.f), glm::vec3(0.f, 0.f, 1.25f));
        pushLine(ref, glm::vec3(0.f), 1.25f * glm::vec3(bsdfWarpOf(p.settings).wo()));
      }
    } else {
      float lo = p.settings.type == WarpType::UniformSquare ? 0.f : -1.f;
      glm::vec3 c[4] = {{lo, lo, 0}, {1, lo, 0}, {1, 1, 0}, {lo, 1, 0}};
      for (int i = 0; i < 4; ++i) pushLine(ref, c[i], c[(i + 1) % 4]);
      if (lo < 0.f) pushCircle(ref, 2, 0.f, 1.f, 128);
    }
    uploadVec4(refVao_, refVbo_, ref);
    refVertexCount_ = ref.size() / 4;
    refKey_ = inspectedName(p.settings);
    refValid_ = true;
  }
}

void WarpInspector::uploadPanels() {
  HistogramPanels hp = makeHistogramPanels(shownVerdict_->chi2);
  panelScale_ = hp.scaleMax;
  if (hp.width <= 0 || hp.observed.empty()) return;
  const std::vector<uint8_t>* imgs[3] = {&hp.observed, &hp.expected, &hp.difference};
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int i = 0; i < 3; ++i) {
    glBindTexture(GL_TEXTURE_2D, panelTex_[i]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, hp.width, hp.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 imgs[i]->data());
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

void WarpInspector::renderScene(int w, int h) {
  w = std::max(w, 16);
  h = std::max(h, 16);
  if (!fbo_ || w != fboW_ || h != fboH_) {
    if (!fbo_) {
      glGenFramebuffers(1, &fbo_);
      glGenTextures(1, &colour_);
      glGenRenderbuffers(1, &depth_);
    }
    glBindTexture(GL_TEXTURE_2D, colour_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour_, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    fboW_ = w;
    fboH_ = h;
    sceneDirty_ = true;
  }
  if (!sceneDirty_) return;
  sceneDirty_ = false;
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w, h);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.07f, 0.07f, 0.08f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  if (shownPoints_) {
    glm::mat4 proj = glm::perspective(glm::radians(35.f), float(w) / float(h), 0.05f, 100.f);
    glm::mat4 view = glm::translate(glm::mat4(1.f), glm::vec3(0, 0, -distance_)) * glm::mat4_cast(rot_);
    glm::mat4 model(1.f);
    if (!shownPoints_->settings.bsdf &&
        shownPoints_->settings.type == WarpType::UniformSquare)  // [0,1]^2 shown as large as [-1,1]^2
      model = glm::scale(glm::mat4(1.f), glm::vec3(2.f)) *
              glm::translate(glm::mat4(1.f), glm::vec3(-0.5f, -0.5f, 0.f));
    glm::mat4 mvp = proj * view * model;
    glUseProgram(program_);
    glUniformMatrix4fv(glGetUniformLocation(program_, "uMvp"), 1, GL_FALSE, &mvp[0][0]);
    GLint colourLoc = glGetUniformLocation(program_, "uColour");
    glEnable(GL_PROGRAM_POINT_SIZE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);

    // reference frame (behind everything: no depth writes)
    glDisable(GL_DEPTH_TEST);
    glUniform4f(colourLoc, 0.45f, 0.45f, 0.5f, 0.6f);
    glBindVertexArray(refVao_);
    glDrawArrays(GL_LINES, 0, GLsizei(refVertexCount_));

    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    int k = shownPoints_->settings.log2Points;
    float size = std::clamp(std::exp2((20.f - k) / 4.5f), 1.f, 6.f);
    glUniform1f(glGetUniformLocation(program_, "uPointSize"), size);
    glBindVertexArray(vao_);
    glDrawArrays(GL_POINTS, 0, GLsizei(pointCount_));
    if (lineVertexCount_ > 0) {
      glDisable(GL_DEPTH_TEST);
      glUniform4f(colourLoc, 1.f, 1.f, 1.f, 0.55f);
      glDrawArrays(GL_LINES, GLint(pointCount_), GLsizei(lineVertexCount_));
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_PROGRAM_POINT_SIZE);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void WarpInspector::drawControls() {
  WarpInspectorSettings& s = settings_;
  ImGui::TextUnformatted("Warp");
  // The warps, then the BSDFs' sampling (microfacet, roughconductor).
  int type = s.bsdf ? kWarpTypeCount + (s.bsdfType == BsdfType::RoughConductor ? 1 : 0) : int(s.type);
  auto typeName = [](void*, int i, const char** out) {
    *out = i < kWarpTypeCount    ? warpTypeName(static_cast<WarpType>(i))
           : i == kWarpTypeCount ? "microfacet (BSDF)"
                                 : "roughconductor (BSDF)";
    return true;
  };
  if (ImGui::Combo("warp", &type, typeName, nullptr, kWarpTypeCount + 2)) {
    if (type < kWarpTypeCount) {
      WarpType t = static_cast<WarpType>(type);
      if (warpHasParameter(t) && (t != s.type || s.bsdf)) s.param = defaultWarpParam(t);
      s.type = t;
      s.bsdf = false;
    } else {
      s.bsdf = true;
      s.bsdfType = type == kWarpTypeCount ? BsdfType::Microfacet : BsdfType::RoughConductor;
    }
  }
  // Values typed into the controls (Ctrl+click on a slider) are checked as `penumbra warp` checks its
  // options: a refused one leaves the settings as they were, and its message shows below.
  auto entered = [this](const std::string& refusal) { refusal_ = refusal; };
  if (s.bsdf) {
    BsdfWarpInputs in = bsdfInputsOf(s);
    float incident = s.incidentDegrees, alpha = s.alpha, kd = s.kd;
    if (ImGui::SliderFloat("incident", &incident, 0.f, float(kMaxIncidentDegrees), "%.2f deg"))
      in.incidentDegrees = incident, entered(enterBsdf(s, in));
    if (ImGui::SliderFloat("alpha", &alpha, 0.005f, 1.5f, "%.4f", ImGuiSliderFlags_Logarithmic))
      in.alpha = alpha, entered(enterBsdf(s, in));
    if (s.bsdfType == BsdfType::Microfacet) {
      if (ImGui::SliderFloat("kd", &kd, 0.f, 1.f, "%.3f")) in.kd = kd, entered(enterBsdf(s, in));
    } else {
      int d = s.distribution == MicrofacetDistribution::Ggx ? 1 : 0;
      const char* names[] = {"beckmann", "ggx"};
      if (ImGui::Combo("distribution", &d, names, 2)) in.distribution = names[d], entered(enterBsdf(s, in));
    }
    hintText(
        "wo = (sin, 0, cos) of the incident angle; rejected draws (below the surface) sit at the centre");
  } else if (warpHasParameter(s.type)) {
    float param = s.param;
    const bool changed = s.type == WarpType::UniformCone
                             ? ImGui::SliderFloat(paramLabel(s.type), &param, -0.99f, 0.999f, "%.3f")
                             : ImGui::SliderFloat(paramLabel(s.type), &param, 0.02f, 1.5f, "%.3f",
                                                  ImGuiSliderFlags_Logarithmic);
    if (changed) entered(enterWarpParam(s, param));
  }
  char countText[48];
  std::snprintf(countText, sizeof countText, "2^%d = %d", s.log2Points, 1 << s.log2Points);
  int log2Points = s.log2Points;
  if (ImGui::SliderInt("points", &log2Points, kMinLog2Points, kMaxLog2Points, countText))
    entered(enterLog2Points(s, log2Points));
  int ps = int(s.pointSet);
  auto psName = [](void*, int i, const char** out) {
    *out = pointSetName(static_cast<PointSet>(i));
    return true;
  };
  if (ImGui::Combo("point set", &ps, psName, nullptr, kPointSetCount)) s.pointSet = static_cast<PointSet>(ps);
  if (s.pointSet == PointSet::Sampler) {
    // The first 2^k samples of one request of a render sampler at one pixel: its nets show as
    // exactly one point per elementary interval.
    if (ImGui::BeginCombo("sampler", std::string(samplerRow(s.sampler).label).c_str())) {
      for (const SamplerRow& row : samplerTable())
        if (ImGui::Selectable(std::string(row.label).c_str(), row.kind == s.sampler)) s.sampler = row.kind;
      ImGui::EndCombo();
    }
    int request = s.request;
    if (ImGui::SliderInt("2-D request", &request, 0, 7, s.request == 0 ? "%d (pixel filter)" : "%d"))
      entered(enterSamplerRequest(s, request));
    int64_t pixel[2] = {s.pixelX, s.pixelY};
    if (ImGui::InputScalarN("pixel", ImGuiDataType_S64, pixel, 2, nullptr, nullptr, nullptr,
                            ImGuiInputTextFlags_EnterReturnsTrue))
      entered(enterSamplerPixel(s, pixel[0], pixel[1]));
  }
  if (!refusal_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.45f, 0.4f, 1.f));
    ImGui::TextWrapped("%s (kept the last valid value)", refusal_.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::Checkbox("warped grid lines", &s.gridLines);
  ImGui::Checkbox("mismatched pdf", &s.mismatch);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Judge the samples by a wrong density (e.g. the uniform one of the same domain)\nto see a "
        "rejection.");
  hintText("judged by %s", judgeDescription(s).c_str());
  if (ImGui::Button("Reset view")) resetView();
  ImGui::SameLine();
  hintText("drag: rotate, wheel: zoom");

  ImGui::Separator();
  ImGui::TextUnformatted("Chi-square test");
  if (!shownVerdict_) {
    hintText("computing...");
    return;
  }
  const WarpVerdict& v = *shownVerdict_;
  const Chi2Result& r = v.chi2;
  bool sphere = v.domain.kind == Chi2Domain::Kind::Sphere;
  ImGui::Text("grid     %d x %d %s", r.resX, r.resY, sphere ? "(phi, cos theta)" : "(x, y)");
  ImGui::Text("pooled   %d cells (expected < 5)", r.pooledCells);
  if (v.settings.bsdf)
    ImGui::Text("rejected %.0f draws (expected %.1f)", r.observedRejected, r.expectedRejected);
  ImGui::Text("chi2     %.2f", r.chi2);
  ImGui::Text("dof      %d", r.dof);
  ImGui::Text("p-value  %.4g", r.pValue);
  ImGui::Text("alpha    %.3g", r.alphaEffective);
  ImGui::TextUnformatted("verdict  ");
  ImGui::SameLine(0, 0);
  if (r.accepted)
    ImGui::TextColored(ImVec4(0.35f, 0.9f, 0.4f, 1.f), "ACCEPTED");
  else
    ImGui::TextColored(ImVec4(1.f, 0.35f, 0.3f, 1.f), "REJECTED");
  if (!r.message.empty()) ImGui::TextWrapped("%s", r.message.c_str());
  if (v.settings.pointSet != PointSet::Independent)
    ImGui::TextWrapped("(%s points are not independent: the test is only indicative)",
                       v.settings.pointSet == PointSet::Sampler ? samplerKindName(v.settings.sampler)
                                                                : pointSetName(v.settings.pointSet));
  if (!upToDate())
    ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "computing...");
  else
    hintText("%d points + quadrature: %.0f ms", 1 << v.settings.log2Points, v.seconds * 1e3);
}

void WarpInspector::drawView(float width, float height) {
  int w = std::max(int(width), 16), h = std::max(int(height), 16);
  renderScene(w, h);
  ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##warp-view", ImVec2(float(w), float(h)));
  ImGui::GetWindowDrawList()->AddImage(texId(colour_), p0, ImVec2(p0.x + w, p0.y + h), ImVec2(0, 1),
                                       ImVec2(1, 0));
  ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsItemActive() && (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    // Arcball: the rotation taking the previous cursor's point on the ball to the current one.
    float cx = p0.x + 0.5f * w, cy = p0.y + 0.5f * h, radius = 0.5f * std::min(w, h);
    auto onBall = [&](ImVec2 m) {
      glm::vec3 p((m.x - cx) / radius, -(m.y - cy) / radius, 0.f);
      float d2 = p.x * p.x + p.y * p.y;
      if (d2 < 1.f)
        p.z = std::sqrt(1.f - d2);
      else
        p = glm::normalize(p);
      return p;
    };
    glm::vec3 a = onBall(ImVec2(io.MousePos.x - io.MouseDelta.x, io.MousePos.y - io.MouseDelta.y));
    glm::vec3 b = onBall(io.MousePos);
    if (glm::length(a - b) > 1e-6f) {
      rot_ = glm::normalize(glm::rotation(a, b) * rot_);
      sceneDirty_ = true;
    }
  }
  if (ImGui::IsItemHovered() && io.MouseWheel != 0) {
    distance_ = std::clamp(distance_ * std::pow(0.9f, io.MouseWheel), 1.2f, 30.f);
    sceneDirty_ = true;
  }
}

namespace {
// The caption under the panels, wrapped to the panels' width (never cut off in a narrow window).
const char* panelsCaption(bool sphere) {
  return sphere
             ? "one colour scale: samples per cell (sample histogram, integrated density, their difference). "
               "Horizontal: phi 0 .. 2pi; vertical: cos theta, 1 at the top"
             : "one colour scale: samples per cell (sample histogram, integrated density, their difference). "
               "Horizontal: x; vertical: y (up)";
}
float panelsCaptionHeight(bool sphere, float width) {
  return ImGui::CalcTextSize(panelsCaption(sphere), nullptr, false, width).y +
         ImGui::GetStyle().ItemSpacing.y;
}
}  // namespace

void WarpInspector::drawPanels(float width) {
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  bool sphere =
      shownVerdict_ ? shownVerdict_->domain.kind == Chi2Domain::Kind::Sphere : showsSphere(settings_);
  float aspect = sphere ? 0.5f : 1.f;  // height / width
  float slot = (width - 2 * spacing) / 3.f;
  float ph = std::min(slot * aspect, 0.36f * ImGui::GetIO().DisplaySize.y);
  float pw = ph / aspect;
  const char* titles[3] = {"histogram", "density", "histogram - density"};
  ImVec2 start = ImGui::GetCursorScreenPos();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (int i = 0; i < 3; ++i) {
    float x = start.x + i * (slot + spacing);
    dl->AddText(ImVec2(x, start.y), ImGui::GetColorU32(ImGuiCol_Text), titles[i]);
    ImVec2 q0(x, start.y + ImGui::GetTextLineHeightWithSpacing());
    ImVec2 q1(q0.x + pw, q0.y + ph);
    if (shownVerdict_) dl->AddImage(texId(panelTex_[i]), q0, q1);
    dl->AddRect(ImVec2(q0.x - 1, q0.y - 1), ImVec2(q1.x + 1, q1.y + 1), IM_COL32(90, 90, 90, 255));
    panelRect_[i][0] = q0.x;
    panelRect_[i][1] = q0.y;
    panelRect_[i][2] = pw;
    panelRect_[i][3] = ph;
  }
  float y = start.y + ImGui::GetTextLineHeightWithSpacing() + ph + 6;
  // Legend: one scale for all three panels (samples per cell).
  char lo[32], hi[32], neg[32];
  std::snprintf(lo, sizeof lo, "0");
  std::snprintf(hi, sizeof hi, "%.0f", panelScale_);
  std::snprintf(neg, sizeof neg, "-%.0f", panelScale_);
  float barH = ImGui::GetTextLineHeight() * 0.8f;
  float hiW = ImGui::CalcTextSize(hi).x, negW = ImGui::CalcTextSize(neg).x;
  // counts: under the histogram and density panels
  float x0 = start.x + ImGui::CalcTextSize(lo).x + 6, x1 = start.x + slot + spacing + pw - hiW - 6;
  dl->AddText(ImVec2(start.x, y), ImGui::GetColorU32(ImGuiCol_Text), lo);
  colourBar(dl, ImVec2(x0, y), ImVec2(x1, y + barH), false);
  dl->AddText(ImVec2(x1 + 6, y), ImGui::GetColorU32(ImGuiCol_Text), hi);
  // signed difference: under the difference panel, the same scale
  float dx = start.x + 2 * (slot + spacing);
  dl->AddText(ImVec2(dx, y), ImGui::GetColorU32(ImGuiCol_Text), neg);
  colourBar(dl, ImVec2(dx + negW + 6, y), ImVec2(dx + pw - hiW - 6, y + barH), true);
  dl->AddText(ImVec2(dx + pw - hiW, y), ImGui::GetColorU32(ImGuiCol_Text), hi);
  y += ImGui::GetTextLineHeightWithSpacing();
  dl->AddText(nullptr, 0.f, ImVec2(start.x, y), ImGui::GetColorU32(ImGuiCol_TextDisabled),
              panelsCaption(sphere), nullptr, width);
  y += panelsCaptionHeight(sphere, width);
  ImGui::Dummy(ImVec2(width, y - start.y));
}

void WarpInspector::draw(bool* open, bool fill) {
  ImGuiIO& io = ImGui::GetIO();
  ImGuiWindowFlags flags =
      ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse;
  if (fill) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(io.DisplaySize);
    flags |= ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
             ImGuiWindowFlags_NoTitleBar;
  } else {
    ImGui::SetNextWindowPos(ImVec2(420, 20), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(
        ImVec2(std::min(1150.f, io.DisplaySize.x - 440), std::min(760.f, io.DisplaySize.y - 40)),
        ImGuiCond_FirstUseEver);
  }
  if (!ImGui::Begin("Warp inspector", open, flags)) {
    ImGui::End();
    return;
  }
  settings_.param = warpHasParameter(settings_.type) ? settings_.param : 0.f;
  worker_.request(settings_);
  auto pts = worker_.points();
  if (pts && pts != shownPoints_) {
    shownPoints_ = pts;
    uploadPoints();
  }
  auto ver = worker_.verdict();
  if (ver && ver != shownVerdict_) {
    shownVerdict_ = ver;
    uploadPanels();
  }
  if (!viewInit_ || viewSpherical_ != showsSphere(settings_)) resetView();

  ImGui::BeginChild("##warp-controls", ImVec2(300, 0), true);
  ImGui::PushItemWidth(-110);
  drawControls();
  ImGui::PopItemWidth();
  ImGui::EndChild();
  ImGui::SameLine();
  ImGui::BeginGroup();
  ImVec2 avail = ImGui::GetContentRegionAvail();
  bool sphere = showsSphere(settings_);
  float slot = (avail.x - 2 * ImGui::GetStyle().ItemSpacing.x) / 3.f;
  float ph = std::min(slot * (sphere ? 0.5f : 1.f), 0.36f * io.DisplaySize.y);
  float panelsH = ph + 2 * ImGui::GetTextLineHeightWithSpacing() + panelsCaptionHeight(sphere, avail.x) + 10 +
                  ImGui::GetStyle().ItemSpacing.y;
  drawView(avail.x, std::max(avail.y - panelsH, 64.f));
  drawPanels(avail.x);
  ImGui::EndGroup();
  ImGui::End();
}

std::string WarpInspector::layoutReport() const {
  std::string out;
  char buf[256];
  for (int i = 0; i < 3; ++i) {
    std::snprintf(buf, sizeof buf, "panel %s %.0f %.0f %.0f %.0f\n", kPanelNames[i], panelRect_[i][0],
                  panelRect_[i][1], panelRect_[i][2], panelRect_[i][3]);
    out += buf;
  }
  if (shownVerdict_) {
    const Chi2Result& r = shownVerdict_->chi2;
    std::snprintf(buf, sizeof buf, "verdict %s chi2 %.3f dof %d p-value %.6g grid %dx%d%s\n",
                  r.accepted ? "accepted" : "rejected", r.chi2, r.dof, r.pValue, r.resX, r.resY,
                  upToDate() ? "" : " (stale)");
    out += buf;
  } else {
    out += "verdict none\n";
  }
  return out;
}

// ---- standalone -------------------------------------------------------------------------------------

int runWarpInspector(const WarpGuiOptions& o) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  int rc = 0;
  {
    platform::WindowOptions wo;
    wo.width = o.windowWidth;
    wo.height = o.windowHeight;
    wo.title = "Penumbra — warp inspector";
    std::unique_ptr<platform::Platform> p = platform::createPlatform(wo);
    WarpInspector inspector(o.settings);
    auto frame = [&] {
      p->pollEvents();
      p->beginFrame();
      ImGui::NewFrame();
      inspector.draw(nullptr, true);
      ImGui::Render();
      int fbW = 0, fbH = 0;
      p->framebufferSize(fbW, fbH);
      glViewport(0, 0, fbW, fbH);
      glClearColor(0.16f, 0.16f, 0.17f, 1.f);
      glClear(GL_COLOR_BUFFER_BIT);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      p->endFrame();
    };
    for (int f = 0; !p->shouldClose() && (o.frames <= 0 || f < o.frames); ++f) {
      if (o.waitForResult && o.frames > 0 && f == o.frames - 1) {
        if (!inspector.worker().waitIdle(120.0))
          std::fprintf(stderr, "warp inspector: the chi-square test did not finish in 120 s\n");
        frame();  // picks up the final points and verdict
      }
      frame();
    }
    if (o.printLayout) std::printf("%s", inspector.layoutReport().c_str());
    if (!o.screenshot.empty()) {
      int w = 0, h = 0;
      std::vector<std::uint8_t> rgb = p->readPixels(w, h);
      Image img(w, h);
      for (size_t i = 0; i < rgb.size(); ++i) img.rgb[i] = srgbToLinear(rgb[i] / 255.f);
      writeImage(o.screenshot, img);
      std::printf("wrote %s (%s)\n", o.screenshot.c_str(), p->name());
    }
  }
  ImGui::DestroyContext();
  return rc;
}

}  // namespace penumbra::ui
