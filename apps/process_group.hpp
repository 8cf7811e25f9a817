// The processes one run is spread over.  Built with MPI (ATTENUVIS_MPI) and
// started by a launcher (`mpirun -np N attenuvis vg ...`), they are MPI's
// world; otherwise this process alone, and the program behaves exactly as a
// build without MPI.  MPI stays in process_group.cpp: the libraries know
// nothing of it (visgraph takes a PassShare with a combine step).
#pragma once

#include <attenuvis/visgraph/space_syntax.hpp>
#include <attenuvis/visgraph/visibility.hpp>

#include <string>

namespace attenuvis::cli {

// Joins MPI's world when a launcher started this process (its environment
// says so); refuses, with a message, a launch on several processes of a build
// without MPI (each would run the whole pass and write the same files).
void start_process_group(int* argc, char*** argv);
// Leaves MPI's world after a run that ended normally on this process.
void finish_process_group();

int process_rank();   // 0 without MPI
int process_count();  // 1 without MPI
inline bool is_root_process() { return process_rank() == 0; }

// This process's share of a visibility pass; with several processes the
// combine step sums the integer accumulators exactly and takes the maxima
// over all of them (every process receives the totals).
visgraph::PassShare process_share();
// This process's share of the space-syntax measures: the graph joined from
// every process's edges (an OR of bit rows, or the pairs gathered), the
// per-node results summed exactly.
visgraph::SpaceSyntaxShare space_syntax_share();

// Waits until every process has come here.  The first process stages its
// outputs only after every other one has passed its last check, so that no
// failure elsewhere can end it (MPI_Abort) with a file half-written.
void synchronize_processes();

// Ends every process of the group with `message` on stderr and a non-zero
// exit status (one process failing must not leave the others waiting).
[[noreturn]] void abort_process_group(const std::string& message);

}  // namespace attenuvis::cli
