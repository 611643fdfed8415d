// MPI plumbing of a batch: start/stop, agreement on errors, broadcast and gather of
// text. Everything else about the distribution (which rank runs which scenario, what
// rank 0 writes) is in batch_run.cpp.
#include "batch_mpi.hpp"

#include <cstdlib>
#include <exception>

#ifdef AVALANCHE_HAVE_MPI
// The C API only: Open MPI's mpi.h would otherwise pull in the deprecated C++ bindings,
// which live in a library (libmpi_cxx) that MPI::MPI_C does not link.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace avalanche::detail {

bool launched_by_mpi() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
        if (std::getenv(v) != nullptr) return true;
    return false;
}

#ifdef AVALANCHE_HAVE_MPI

namespace {

struct Status {
    int code = 0;
    std::string message;
};

}  // namespace

BatchRanks::BatchRanks() {
    int finalized = 0, initialised = 0;
    MPI_Finalized(&finalized);
    MPI_Initialized(&initialised);
    // Not launched by MPI: no singleton MPI_Init (it would start Open MPI's runtime for
    // nothing, print warnings on machines without a network, and refuse root).
    if (finalized || !launched_by_mpi()) return;
    if (!initialised) {
        int provided = 0;
        MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
        initialised_here_ = true;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local_size_);
    MPI_Comm_free(&node);
}

BatchRanks::~BatchRanks() {
    if (initialised_here_) MPI_Finalize();
}

std::string BatchRanks::broadcast(const std::string& from_root) const {
    if (size_ == 1) return from_root;
    std::string text = from_root;
    int length = static_cast<int>(text.size());
    MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
    text.resize(static_cast<std::size_t>(length));
    if (length > 0) MPI_Bcast(text.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
    return text;
}

int BatchRanks::broadcast_code(int from_root) const {
    int code = from_root;
    if (size_ > 1) MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return code;
}

std::vector<std::string> BatchRanks::gather(const std::string& mine) const {
    if (size_ == 1) return {mine};
    int length = static_cast<int>(mine.size());
    std::vector<int> lengths(static_cast<std::size_t>(size_)), offsets(lengths.size());
    MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string all;
    if (root()) {
        int total = 0;
        for (std::size_t r = 0; r < lengths.size(); ++r) {
            offsets[r] = total;
            total += lengths[r];
        }
        all.resize(static_cast<std::size_t>(total));
    }
    MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
                0, MPI_COMM_WORLD);
    std::vector<std::string> out;
    if (root())
        for (std::size_t r = 0; r < lengths.size(); ++r)
            out.push_back(all.substr(static_cast<std::size_t>(offsets[r]),
                                     static_cast<std::size_t>(lengths[r])));
    return out;
}

void BatchRanks::all_or_none(const std::function<void()>& step) const {
    if (size_ == 1) {
        step();
        return;
    }
    Status local;
    std::exception_ptr error;
    try {
        step();
    } catch (const Error& e) {
        local = {static_cast<int>(e.code()), e.what()};
        error = std::current_exception();
    } catch (const std::exception& e) {
        local = {static_cast<int>(ExitCode::internal), std::string("internal error: ") + e.what()};
        error = std::current_exception();
    }
    // The lowest failing rank speaks: its number is the smallest of (rank if failed, size).
    int candidate = local.code != 0 ? rank_ : size_, first = size_;
    MPI_Allreduce(&candidate, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size_) return;
    Status agreed = local;
    if (first != 0) {  // bring the failing rank's error to rank 0
        if (rank_ == first) {
            int length = static_cast<int>(local.message.size());
            MPI_Send(&local.code, 1, MPI_INT, 0, 0, MPI_COMM_WORLD);
            MPI_Send(&length, 1, MPI_INT, 0, 1, MPI_COMM_WORLD);
            MPI_Send(local.message.data(), length, MPI_CHAR, 0, 2, MPI_COMM_WORLD);
        } else if (root()) {
            int length = 0;
            MPI_Recv(&agreed.code, 1, MPI_INT, first, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            MPI_Recv(&length, 1, MPI_INT, first, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            agreed.message.resize(static_cast<std::size_t>(length));
            MPI_Recv(agreed.message.data(), length, MPI_CHAR, first, 2, MPI_COMM_WORLD,
                     MPI_STATUS_IGNORE);
            agreed.message = "rank " + std::to_string(first) + ": " + agreed.message;
        }
    }
    const int code = broadcast_code(agreed.code);
    if (root() && first == 0) std::rethrow_exception(error);  // its own error, as thrown
    if (root()) throw Error(static_cast<ExitCode>(code), agreed.message);
    throw QuietRankExit{code};
}

#else  // one process: every collective is the identity

// Under mpirun, a build without MPI would run N full copies of the batch into one DIR.
BatchRanks::BatchRanks() {
    if (launched_by_mpi())
        throw Error(ExitCode::usage,
                    "this build has no MPI support (built with AVALANCHE_WITH_MPI=OFF); run "
                    "the batch without mpirun/srun, or rebuild with MPI");
}
BatchRanks::~BatchRanks() = default;
void BatchRanks::all_or_none(const std::function<void()>& step) const { step(); }
std::string BatchRanks::broadcast(const std::string& from_root) const { return from_root; }
std::vector<std::string> BatchRanks::gather(const std::string& mine) const { return {mine}; }
int BatchRanks::broadcast_code(int from_root) const { return from_root; }

#endif

}  // namespace avalanche::detail
