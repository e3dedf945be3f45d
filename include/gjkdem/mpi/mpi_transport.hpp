#pragma once
// Domains over MPI (dem::DomainTransport): `mpirun -np N gjkdem run` runs
// one scene on N ranks. The library gjkdem::gjkdem_mpi is built with MPI
// where CMake finds it (Debian's libopenmpi-dev); without, it answers null.
#include <memory>

#include "gjkdem/dem/domains.hpp"

namespace gjkdem::mpi {

/// MPI, initialised when this process was started by an MPI launcher
/// (mpirun, mpiexec, srun) with more than one rank, and finalised when the
/// last handle goes; null otherwise (a plain `gjkdem run`, or a build
/// without MPI).
std::unique_ptr<dem::DomainTransport> launched_transport();

/// Ends every rank of the job now (MPI_Abort) with `status`: for a rank that
/// fails outside the run's agreements (an exception out of a domain run),
/// which the others would otherwise wait for in their next exchange, for
/// ever. Without MPI, exits this process.
[[noreturn]] void abort_job(int status);

}  // namespace gjkdem::mpi
