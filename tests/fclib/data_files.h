#pragma once

// The FCLIB problems of tests/fclib/data (a copy of ../shared/fclib), by
// name without ".hdf5": the files every solver test runs over.

#include <string>
#include <vector>

namespace fclib_test_data
{
  inline const std::vector<std::string> names = {
    "Box_Stacks-i0122-82-5",
    "Capsules-i125-1213",
    "CubeH8",
    "LMGC_100_PR_PerioBox-i00361-60-03000",
    "LMGC_GlobalFrictionContactProblem00046",
    "Spheres-i099-356-679",
    "local_problem_test",
    "spheres-in-a-box-98-i10000-256-10"};
} // namespace fclib_test_data
