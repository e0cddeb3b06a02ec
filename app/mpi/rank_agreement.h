// The steps at which the ranks of `penumbra-mpi render` agree before rendering together. Every rank
// calls each of them, in the same order, whatever happened to it: a rank that failed or disagrees
// still takes part, so that every rank learns of it and exits instead of waiting in a collective
// for a rank that has left. Rank 0 prints what went wrong, once.
#pragma once

#include <string>

#include "app/mpi/mpi_session.h"
#include "app/mpi/run_description.h"

namespace penumbra::mpi {

// `failure` is what went wrong on this rank ("" for nothing). True when no rank failed; otherwise
// rank 0 prints every distinct failure once, naming the ranks it happened on, and false on every rank.
bool everyRankSucceeded(const Session& session, const std::string& failure);

// True when every rank's description has rank 0's digest. Otherwise the ranks exchange the details
// and rank 0 prints, for each disagreeing rank, the first setting it disagrees on ("rank 1 disagrees
// with rank 0 on camera.width: 64 vs 128"), and false on every rank.
bool everyRankAgrees(const Session& session, const RunDescription& description);

}  // namespace penumbra::mpi
