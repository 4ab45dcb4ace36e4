// mpi_plugin.cpp: libmontecl_mpi.so (job/mpi_plugin_abi.h), the only code that links MPI.
#include <mpi.h>
#include <stdio.h>
#include <time.h>

#include "job/mpi_plugin_abi.h"

namespace {

int waitPolling(MPI_Request* request) {
  int done = 0;
  for (int spins = 0;; ++spins) {
    if (MPI_Test(request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) return 1;
    if (done) return 0;
    if (spins > 100) {
      timespec t{0, 200000};  // 0.2 ms
      nanosleep(&t, nullptr);
    }
  }
}

int init(int* rank, int* size, int* localRank, char* err, int errLen) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized && MPI_Init(nullptr, nullptr) != MPI_SUCCESS) {
    snprintf(err, size_t(errLen), "MPI_Init failed");
    return 1;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, *rank, MPI_INFO_NULL, &node);
  MPI_Comm_rank(node, localRank);
  MPI_Comm_free(&node);
  return 0;
}

int allreduceSum(uint64_t* values, int n) {
  MPI_Request r;
  if (MPI_Iallreduce(MPI_IN_PLACE, values, n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD, &r) != MPI_SUCCESS) return 1;
  return waitPolling(&r);
}

int gatherBytes(const void* send, int sendBytes, void* recv, const int* recvCounts, const int* displs) {
  MPI_Request r;
  if (MPI_Igatherv(send, sendBytes, MPI_BYTE, recv, recvCounts, displs, MPI_BYTE, 0, MPI_COMM_WORLD, &r) !=
      MPI_SUCCESS)
    return 1;
  return waitPolling(&r);
}

void abortAll(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

void finalize() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

const MonteclMpiApi kApi = {init, allreduceSum, gatherBytes, abortAll, finalize};

}  // namespace

extern "C" __attribute__((visibility("default"))) const MonteclMpiApi* montecl_mpi_api_v1() { return &kApi; }
