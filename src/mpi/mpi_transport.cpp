#include "gjkdem/mpi/mpi_transport.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef GJKDEM_HAVE_MPI
#include <mpi.h>
#endif

namespace gjkdem::mpi {

#ifdef GJKDEM_HAVE_MPI
namespace {

// Two collectives per exchange: the byte counts, then the bytes.
class MpiTransport : public dem::DomainTransport {
 public:
  MpiTransport() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiTransport() override { MPI_Finalize(); }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::vector<std::string> exchange(std::vector<std::string> out) override {
    const std::size_t n = static_cast<std::size_t>(size_);
    std::vector<int> send_counts(n), send_at(n), receive_counts(n), receive_at(n);
    std::string send;
    for (std::size_t r = 0; r < n; ++r) {
      if (out[r].size() + send.size() > static_cast<std::size_t>(INT32_MAX))
        throw std::runtime_error("a domain message exceeds 2 GiB (use more ranks)");
      send_at[r] = static_cast<int>(send.size());
      send_counts[r] = static_cast<int>(out[r].size());
      send += out[r];
    }
    MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::size_t total = 0;
    for (std::size_t r = 0; r < n; ++r) {
      receive_at[r] = static_cast<int>(total);
      total += static_cast<std::size_t>(receive_counts[r]);
    }
    if (total > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("domain messages exceed 2 GiB (use more ranks)");
    std::string receive(total, '\0');
    MPI_Alltoallv(send.data(), send_counts.data(), send_at.data(), MPI_BYTE, receive.data(), receive_counts.data(),
                  receive_at.data(), MPI_BYTE, MPI_COMM_WORLD);
    std::vector<std::string> in(n);
    for (std::size_t r = 0; r < n; ++r) in[r] = receive.substr(receive_at[r], receive_counts[r]);
    return in;
  }

 private:
  int rank_ = 0, size_ = 1;
};

// Set by Open MPI's, MPICH's and Slurm's launchers.
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "SLURM_NTASKS"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace

std::unique_ptr<dem::DomainTransport> launched_transport() {
  if (!launched_by_mpi()) return nullptr;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) MPI_Init(nullptr, nullptr);
  auto t = std::make_unique<MpiTransport>();
  return t;  // one rank too: the caller runs the whole world then
}

void abort_job(int status) {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (initialised && !finalised) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

#else

std::unique_ptr<dem::DomainTransport> launched_transport() { return nullptr; }

void abort_job(int status) { std::exit(status); }

#endif

}  // namespace gjkdem::mpi
