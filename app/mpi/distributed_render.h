// `penumbra-mpi render`: one render shared by the ranks of an MPI job. Every rank loads the scene
// and renders its own aligned blocks of sample indices (SampleSchedule::blocks: rank r of K renders
// blocks r, r+K, r+2K, ... of `block` indices) with its threads; the ranks meet after each block to
// agree on whether to go on (time limit on rank 0, an interrupt on any rank); the film sums are then
// reduced onto rank 0, which writes the image, its standard error and the metadata.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>

#include "app/cli/scene_options.h"
#include "app/mpi/mpi_session.h"

namespace penumbra::mpi {

// Exit code of a render stopped by SIGINT, SIGTERM or SIGUSR1 whose partial image was written.
inline constexpr int kExitInterrupted = 3;
// Exit code of a job in which some rank failed before the render, or the ranks disagree on what to
// render: nothing was rendered or written.
inline constexpr int kExitBadInput = 2;

struct DistributedRenderOptions {
  cli::SceneOptions scene;
  std::string output;
  uint32_t spp = 0;
  double seconds = 0;
  std::optional<uint64_t> seed;  // default: the scene's (or the reference seed)
  int threads = 0;
  uint32_t block = 16;
  bool reference = false;
};

// The `render` subcommand's options, parsed into `options` (no MPI: parsing runs on every rank alone).
CLI::App* addDistributedRenderCommand(CLI::App& app, DistributedRenderOptions& options);

// Every rank calls it after parsing its arguments and agreeing that every rank parsed them. It
// prepares the render (scene, output, settings), agrees with the other ranks that every rank
// prepared it and would render the same image (rank_agreement.h), renders, and rank 0 writes.
// Returns the exit code: 0, kExitBadInput (nothing rendered) or kExitInterrupted. Throws on a
// failure after the ranks agreed to render (the caller ends the job).
int runDistributedRender(const DistributedRenderOptions& options, const Session& session);

}  // namespace penumbra::mpi
