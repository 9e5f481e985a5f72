// main() of the unit tests that need PETSc (the material registry reads PETSc options): GoogleTest
// takes its --gtest_* arguments first, PETSc gets the rest (so -info etc. still work).
#include "material.hpp"

#include <gtest/gtest.h>
#include <petscsys.h>

int main(int argc, char **argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, "burst unit tests") != 0) return 2;
  const int rc = RUN_ALL_TESTS();
  if (burst::MaterialRegistryDestroy() != 0) return 3;
  if (PetscFinalize() != 0) return 4;
  return rc;
}
