// --display-server HOST[:PORT] of render, view and converge: stream the image to a running tev
// (app/net). Resolved before anything renders, so a bad or unknown host is an argument error.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/net/tev_streamer.h"
#include "core/integrators/integrator_desc.h"

namespace penumbra::cli {

struct DisplayServerOption {
  std::string spec;  // empty: not streaming

  void addTo(CLI::App& cmd);
  // The resolved server, or nullopt without the option. Throws penumbra::Error (exit code 2) on a
  // malformed value or a host that does not resolve.
  std::optional<net::DisplayServer> resolve() const;
};

// A streamer connecting to `server` (nullptr for none).
std::unique_ptr<net::TevStreamer> openStream(const std::optional<net::DisplayServer>& server,
                                             net::TevStreamOptions options = {});

// The name of an image in tev: the scene file's stem and the strategy, e.g. "sphere-area [area]"
// ("built-in" for the built-in scene), then `suffix` (converge: " converge").
std::string tevImageName(const std::string& scenePath, const IntegratorDesc& integrator,
                         const std::string& suffix = "");

}  // namespace penumbra::cli
