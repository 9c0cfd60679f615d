#include <util/blas_kernels.h>

#include <dlfcn.h>

#include <cstdlib>

namespace dualcontact
{
  namespace util
  {
    std::string
    blas_core_name()
    {
      // an OpenBLAS extension: looked up at run time, so that another BLAS
      // (reference BLAS, BLIS) links and runs unchanged
      using CoreName   = char *(*)();
      const auto query = reinterpret_cast<CoreName>(
        dlsym(RTLD_DEFAULT, "openblas_get_corename"));
      if (query == nullptr)
        return "";
      const char *name = query();
      return name != nullptr ? name : "";
    }


    std::string
    blas_kernel_choice()
    {
      if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
        return "";
      const std::string before = blas_core_name();
      if (before != "Prescott" && before != "prescott")
        return "";
      __builtin_cpu_init();
      const char *core = nullptr;
      if (__builtin_cpu_supports("avx512f") &&
          __builtin_cpu_supports("avx512cd") &&
          __builtin_cpu_supports("avx512bw") &&
          __builtin_cpu_supports("avx512dq") &&
          __builtin_cpu_supports("avx512vl"))
        core = "SkylakeX";
      else if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        core = "Haswell";
      if (core == nullptr)
        return "";
      using Function  = void (*)();
      const auto quit = reinterpret_cast<Function>(
        dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
      const auto init = reinterpret_cast<Function>(
        dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));
      if (quit == nullptr || init == nullptr ||
          setenv("OPENBLAS_CORETYPE", core, 1) != 0)
        return "";
      // OpenBLAS reads the variable when it chooses its kernels
      quit();
      init();
      return std::string("OPENBLAS_CORETYPE=") + core + " (OpenBLAS chose " +
             before + ", now " + blas_core_name() + ")";
    }
  } // namespace util
} // namespace dualcontact
