#pragma once
// The processes of a batch launched by MPI (`mpirun -n N avalanche-hazard batch ...`,
// or srun under Slurm): docs/batch.md, "Many machines (MPI)". Without an MPI launcher,
// or in a build without MPI, a batch is one rank of one and none of this calls MPI, so
// `run`, the tests and a plain `batch` never initialise MPI.
#include <functional>
#include <string>
#include <vector>

#include "avalanche/core/error.hpp"

namespace avalanche::detail {

// Thrown on ranks other than 0 when the batch stops with an error that rank 0 reports:
// the command returns the exit code without printing, so the user sees one error line.
struct QuietRankExit {
    int code;
};

class BatchRanks {
  public:
    // Initialises MPI (thread level "funneled": only the main thread calls MPI, the
    // scenario threads do not) when an MPI launcher started the process, else one rank.
    BatchRanks();
    ~BatchRanks();  // MPI_Finalize if initialised here
    BatchRanks(const BatchRanks&) = delete;
    BatchRanks& operator=(const BatchRanks&) = delete;

    [[nodiscard]] int rank() const { return rank_; }
    [[nodiscard]] int size() const { return size_; }
    [[nodiscard]] bool root() const { return rank_ == 0; }
    // Ranks on this machine (shared memory), to share its cores between them.
    [[nodiscard]] int ranks_on_node() const { return local_size_; }

    // Runs `step` (on every rank; it may do nothing on some) and makes the ranks agree on
    // its outcome: if it threw an Error on any rank, rank 0 throws the error of the lowest
    // failing rank and every other rank throws QuietRankExit. With one rank, `step` runs
    // as is and its exceptions propagate untouched.
    void all_or_none(const std::function<void()>& step) const;

    // Rank 0's text on every rank.
    [[nodiscard]] std::string broadcast(const std::string& from_root) const;
    // Every rank's text on rank 0, in rank order (empty on other ranks).
    [[nodiscard]] std::vector<std::string> gather(const std::string& mine) const;
    // Rank 0's exit code on every rank.
    [[nodiscard]] int broadcast_code(int from_root) const;

  private:
    int rank_ = 0, size_ = 1, local_size_ = 1;
    bool initialised_here_ = false;
};

// Whether an MPI launcher (Open MPI's mpirun, a PMI/PMIx launcher such as srun or
// MPICH's hydra) started this process: the variables each of them sets for its ranks.
bool launched_by_mpi();

}  // namespace avalanche::detail
