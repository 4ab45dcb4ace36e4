// mpi_plugin_abi.h: the C interface of libmontecl_mpi.so, the module that links the MPI library
// (built only when CMake finds MPI; dlopened by job/mpi.cpp only when the process was launched by
// MPI), so a plain `montecl render` never loads MPI and a build without MPI builds the rest.
#pragma once
#include <stdint.h>

extern "C" {
struct MonteclMpiApi {
  // MPI_Init; rank and size in MPI_COMM_WORLD, rank among the node's ranks (MPI_Comm_split_type
  // SHARED). 0 on success, else writes a message to err.
  int (*init)(int* rank, int* size, int* localRank, char* err, int errLen);
  // In-place sum over all ranks of n uint64 values; waits by polling with short sleeps (a rank
  // that waits does not spin a core away from the ranks still rendering).
  int (*allreduceSum)(uint64_t* values, int n);
  // Gathers each rank's sendBytes to rank 0 at displs[r] of recv (recvCounts, displs: rank 0 only).
  int (*gatherBytes)(const void* send, int sendBytes, void* recv, const int* recvCounts, const int* displs);
  void (*abortAll)(int code);
  void (*finalize)(void);
};
typedef const MonteclMpiApi* (*MonteclMpiApiFn)(void);
}
#define MONTECL_MPI_API_SYMBOL "montecl_mpi_api_v1"
