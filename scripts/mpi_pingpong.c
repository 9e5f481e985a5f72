/* Ping-pong between ranks 0 and 1 (scripts/scaling_model.py times): for each message size prints the
 * size (bytes) and half the round-trip time (s), the best of 5 rounds of 200 round trips, so that a
 * fit t = alpha + n / beta gives the latency and bandwidth the model charges per ghost message. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  int rank;
  MPI_Init(&argc, &argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int sizes[] = {8, 1024, 8192, 65536, 262144, 1048576};
  char     *buf     = calloc(1048576, 1);
  if (!rank) printf("# bytes half_round_trip_s\n");
  for (int s = 0; s < 6; ++s) {
    double best = 1e30;
    for (int round = 0; round < 5; ++round) {
      const int reps = 200;
      MPI_Barrier(MPI_COMM_WORLD);
      const double t0 = MPI_Wtime();
      for (int r = 0; r < reps; ++r) {
        if (rank == 0) {
          MPI_Send(buf, sizes[s], MPI_CHAR, 1, 0, MPI_COMM_WORLD);
          MPI_Recv(buf, sizes[s], MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        } else if (rank == 1) {
          MPI_Recv(buf, sizes[s], MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
          MPI_Send(buf, sizes[s], MPI_CHAR, 0, 0, MPI_COMM_WORLD);
        }
      }
      const double t = (MPI_Wtime() - t0) / (2.0 * reps);
      if (t < best) best = t;
    }
    if (!rank) printf("%d %.9e\n", sizes[s], best);
  }
  free(buf);
  MPI_Finalize();
  return 0;
}
