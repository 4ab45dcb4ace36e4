// mpi.h: the MPI job this process belongs to, if any. MPI is used only when the environment says
// the process was launched by an MPI launcher (launchedByMpi); then libmontecl_mpi.so is dlopened
// (job/mpi_plugin_abi.h) and MPI_Init runs; otherwise nothing MPI is loaded.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace montecl::jobs {

// The launch rule: MONTECL_MPI=0 never, =1 always; else MPI when any of OMPI_COMM_WORLD_SIZE
// (Open MPI's mpirun), PMI_SIZE (MPICH/Hydra, Intel MPI), PMIX_RANK (PMIx launchers, srun
// --mpi=pmix) is set, or SLURM_PROCID is set with SLURM_NTASKS > 1 (srun).
bool launchedByMpi();

struct World {
  bool active = false;  // MPI initialised (launchedByMpi and the module loaded)
  int rank = 0, size = 1, localRank = 0;
};

// Joins the MPI job on first call when launchedByMpi() (MPI_Finalize at exit); a module that
// cannot load or an MPI_Init that fails is a RuntimeError.
const World& world();

// Sum over ranks, in place (no-op without MPI).
void allreduceSum(std::vector<std::uint64_t>& values);
// Gathers each rank's bytes at rank 0 (offsets and sizes: rank 0 only).
void gatherBytes(const std::string& send, std::string& recv, const std::vector<int>& sizes,
                 const std::vector<int>& offsets);

// For main's error path: under MPI ends the whole job (MPI_Abort with code; never returns);
// otherwise returns code.
int failed(int code);

}  // namespace montecl::jobs
