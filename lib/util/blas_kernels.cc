#include <util/blas_kernels.h>

#include <dlfcn.h>
#include <unistd.h>

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


    void
    use_fast_blas_kernels(char **argv)
    {
      if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
        return; // the user's choice (and the re-executed program)
      const std::string core = blas_core_name();
      if (core != "Prescott" && core != "prescott")
        return;
      __builtin_cpu_init();
      if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
        return;
      if (setenv("OPENBLAS_CORETYPE", "Haswell", 1) != 0)
        return;
      execv("/proc/self/exe", argv);
      // the exec failed: go on with the kernels loaded
      unsetenv("OPENBLAS_CORETYPE");
    }
  } // namespace util
} // namespace dualcontact
