// `penumbra-mpi render`: one render shared by the ranks of an MPI job. Every rank loads the scene
// and renders its own aligned blocks of sample indices (SampleSchedule::blocks: rank r of K renders
// blocks r, r+K, r+2K, ... of `block` indices) with its threads; the ranks meet after each block to
// agree on whether to go on (time limit on rank 0, an interrupt on any rank); the film sums are then
// reduced onto rank 0, which writes the image, its standard error and the metadata.
#pragma once

#include <CLI/CLI.hpp>

#include "app/mpi/mpi_session.h"

namespace penumbra::mpi {

// Exit code of a render stopped by SIGINT, SIGTERM or SIGUSR1 whose partial image was written.
inline constexpr int kExitInterrupted = 3;

void addDistributedRenderCommand(CLI::App& app, const Session& session, int& exitCode);

}  // namespace penumbra::mpi
