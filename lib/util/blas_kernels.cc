#include <util/blas_kernels.h>

#include <dlfcn.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

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


    namespace
    {
      /** blas_kernel_choice()'s first answer, for blas_kernel_report(). */
      std::string first_choice;
      bool        chosen = false;

      /** The choice itself (see blas_kernel_choice()). */
      std::string
      choose_kernels();

      /** An OpenBLAS extension looked up at run time (null: not there). */
      template <typename Function>
      Function
      openblas_function(const char *name)
      {
        return reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, name));
      }
    } // namespace


    std::string
    blas_kernel_report()
    {
      if (!first_choice.empty())
        return first_choice;
      const char *user = std::getenv("OPENBLAS_CORETYPE");
      if (chosen && user != nullptr)
        return std::string("OPENBLAS_CORETYPE=") + user + " set by the user";
      return "OpenBLAS' own choice";
    }


    int
    blas_threads()
    {
      const auto get = openblas_function<int (*)()>("openblas_get_num_threads");
      return get != nullptr ? get() : 0;
    }


    void
    set_blas_threads(const int n)
    {
      const auto set =
        openblas_function<void (*)(int)>("openblas_set_num_threads");
      if (set != nullptr)
        set(n);
    }


    BlasThreadChoice
    automatic_blas_threads(const unsigned int n_processes)
    {
      if (n_processes > 1)
        return {1, "one per process under MPI"};
      for (const char *variable : {"OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"})
        if (const char *value = std::getenv(variable); value != nullptr)
          return {0, std::string(variable) + "=" + value + " set by the user"};
      cpu_set_t cpus;
      CPU_ZERO(&cpus);
      const int cores = sched_getaffinity(0, sizeof(cpus), &cpus) == 0 ?
                          CPU_COUNT(&cpus) :
                          static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
      double    load  = 0;
      if (getloadavg(&load, 1) != 1)
        load = 0;
      const int idle =
        static_cast<int>(std::floor(std::max(cores, 1) - load + 0.5));
      std::ostringstream reason;
      reason << "automatic: load average " << std::fixed << std::setprecision(2)
             << load << " on " << cores << " core" << (cores == 1 ? "" : "s");
      return {std::clamp(idle, 1, std::max(cores, 1)), reason.str()};
    }


    void
    use_blas_threads(const BlasThreadChoice &choice)
    {
      if (choice.threads > 0)
        set_blas_threads(choice.threads);
    }


    std::string
    blas_kernel_choice()
    {
      const bool first         = !chosen;
      chosen                   = true;
      const std::string choice = choose_kernels();
      if (first)
        first_choice = choice;
      return choice;
    }


    namespace
    {
      std::string
      choose_kernels()
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
        else if (__builtin_cpu_supports("avx2") &&
                 __builtin_cpu_supports("fma"))
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
    } // namespace
  }   // namespace util
} // namespace dualcontact
