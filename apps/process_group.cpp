// MPI's world, or one process (process_group.hpp).
#include "process_group.hpp"

#include <algorithm>
#include <string>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <vector>

#ifdef ATTENUVIS_WITH_MPI
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace attenuvis::cli {
namespace {
int rank_ = 0, count_ = 1;

// The number of processes a launcher started, from the environment it sets
// (OpenMPI's mpirun, or a PMI launcher such as srun); 0 when not launched.
int launched_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return std::getenv("PMIX_RANK") ? 1 : 0;
}
}  // namespace

#ifdef ATTENUVIS_WITH_MPI
namespace {
bool joined_ = false;
}

void start_process_group(int* argc, char*** argv) {
  if (launched_processes() == 0) return;
  // Only the main thread calls MPI (the pass's worker threads never do).
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  joined_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &count_);
}

void finish_process_group() {
  if (joined_) MPI_Finalize();
  joined_ = false;
}

visgraph::PassShare process_share() {
  visgraph::PassShare share;
  share.index = rank_;
  share.count = count_;
  if (count_ > 1)
    share.combine = [](std::vector<std::int64_t>& sums, std::vector<double>& maxima) {
      // MPI counts are int: reduce in chunks of at most 2^30 elements.
      constexpr std::size_t kChunk = std::size_t{1} << 30;
      for (std::size_t at = 0; at < sums.size(); at += kChunk)
        if (MPI_Allreduce(MPI_IN_PLACE, sums.data() + at, static_cast<int>(std::min(kChunk, sums.size() - at)),
                          MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD) != MPI_SUCCESS)
          throw std::runtime_error("MPI: the sum of the visibility accumulators failed");
      for (std::size_t at = 0; at < maxima.size(); at += kChunk)
        if (MPI_Allreduce(MPI_IN_PLACE, maxima.data() + at, static_cast<int>(std::min(kChunk, maxima.size() - at)),
                          MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD) != MPI_SUCCESS)
          throw std::runtime_error("MPI: the maximum of the visible distances failed");
    };
  return share;
}

namespace {
// MPI counts are int: every collective below goes in chunks of at most 2^30 elements.
constexpr std::size_t kChunk = std::size_t{1} << 30;

template <class T>
void all_reduce(std::vector<T>& v, MPI_Datatype type, MPI_Op op, const char* what) {
  for (std::size_t at = 0; at < v.size(); at += kChunk)
    if (MPI_Allreduce(MPI_IN_PLACE, v.data() + at, static_cast<int>(std::min(kChunk, v.size() - at)), type, op,
                      MPI_COMM_WORLD) != MPI_SUCCESS)
      throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

// Every process's vector, concatenated in process order, on every process:
// the lengths first, then each process's part broadcast from it.
void all_gather(std::vector<std::uint64_t>& v) {
  std::vector<std::uint64_t> lengths(static_cast<std::size_t>(count_), 0);
  lengths[static_cast<std::size_t>(rank_)] = v.size();
  all_reduce(lengths, MPI_UINT64_T, MPI_SUM, "the sizes of the edge lists");
  std::vector<std::uint64_t> all;
  for (int r = 0; r < count_; ++r) {
    std::vector<std::uint64_t> part = r == rank_ ? v : std::vector<std::uint64_t>(lengths[static_cast<std::size_t>(r)]);
    for (std::size_t at = 0; at < part.size(); at += kChunk)
      if (MPI_Bcast(part.data() + at, static_cast<int>(std::min(kChunk, part.size() - at)), MPI_UINT64_T, r,
                    MPI_COMM_WORLD) != MPI_SUCCESS)
        throw std::runtime_error("MPI: gathering the lines of sight failed");
    all.insert(all.end(), part.begin(), part.end());
  }
  v.swap(all);
}
}  // namespace

visgraph::SpaceSyntaxShare space_syntax_share() {
  visgraph::SpaceSyntaxShare share;
  share.index = rank_;
  share.count = count_;
  if (count_ > 1) {
    share.or_words = [](std::vector<std::uint64_t>& v) { all_reduce(v, MPI_UINT64_T, MPI_BOR, "joining the graph's bit rows"); };
    share.gather = [](std::vector<std::uint64_t>& v) { all_gather(v); };
    share.sum = [](std::vector<double>& v) { all_reduce(v, MPI_DOUBLE, MPI_SUM, "joining the space-syntax measures"); };
    share.sum_integers = [](std::vector<std::int64_t>& v) {
      all_reduce(v, MPI_INT64_T, MPI_SUM, "joining the through-vision counts");
    };
  }
  return share;
}

void synchronize_processes() {
  if (joined_ && count_ > 1 && MPI_Barrier(MPI_COMM_WORLD) != MPI_SUCCESS)
    throw std::runtime_error("MPI: the processes could not meet before writing the outputs");
}

void abort_process_group(const std::string& message) {
  std::cerr << message << std::flush;
  if (joined_ && count_ > 1) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

#else

void start_process_group(int*, char***) {
  if (launched_processes() > 1) {
    std::cerr << "attenuvis: error: started on " << launched_processes()
              << " processes, but this build has no MPI (configure with -DATTENUVIS_MPI=ON where libopenmpi-dev "
                 "is installed), so each would run the whole work and write the same files; run one process\n";
    std::exit(1);
  }
}
void finish_process_group() {}
visgraph::PassShare process_share() { return {}; }
visgraph::SpaceSyntaxShare space_syntax_share() { return {}; }
void synchronize_processes() {}
void abort_process_group(const std::string& message) {
  std::cerr << message << std::flush;
  std::exit(1);
}

#endif

int process_rank() { return rank_; }
int process_count() { return count_; }

}  // namespace attenuvis::cli
