#include "app/cli/display_server_option.h"

#include <filesystem>

#include "core/analysis/convergence.h"

namespace penumbra::cli {

void DisplayServerOption::addTo(CLI::App& cmd) {
  cmd.add_option("--display-server", spec,
                 "Stream the image to tev (github.com/Tom94/tev) listening at HOST[:PORT] (default port "
                 "14158, tev's); tev not running is a warning, the render goes on")
      ->type_name("HOST[:PORT]")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return text.empty() ? "expected HOST or HOST:PORT, e.g. 127.0.0.1:14158, got an empty value" : "";
          },
          "HOST[:PORT]"));
}

std::optional<net::DisplayServer> DisplayServerOption::resolve() const {
  if (spec.empty()) return std::nullopt;
  return net::resolveDisplayServer(spec);
}

std::unique_ptr<net::TevStreamer> openStream(const std::optional<net::DisplayServer>& server,
                                             net::TevStreamOptions options) {
  return server ? std::make_unique<net::TevStreamer>(*server, std::move(options)) : nullptr;
}

std::string tevImageName(const std::string& scenePath, const IntegratorDesc& integrator,
                         const std::string& suffix) {
  const std::string scene = scenePath.empty() ? "built-in" : std::filesystem::path(scenePath).stem().string();
  return scene + " [" + strategyShortName(integrator) + "]" + suffix;
}

}  // namespace penumbra::cli
