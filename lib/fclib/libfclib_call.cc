#include <deal.II/base/exceptions.h>

#include <fclib/libfclib_call.h>

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace dualcontact
{
  namespace fclib
  {
    namespace
    {
      /** The call in progress, for the handler exit() runs. */
      struct ActiveCall
      {
        bool        active = false;
        std::string file;
        std::string action;
        std::string partial_file;
        int         saved_stderr = -1;
      };

      ActiveCall &
      active_call()
      {
        static ActiveCall call;
        return call;
      }

      void
      restore_stderr(ActiveCall &call)
      {
        if (call.saved_stderr < 0)
          return;
        std::fflush(stderr);
        dup2(call.saved_stderr, STDERR_FILENO);
        close(call.saved_stderr);
        call.saved_stderr = -1;
      }

      /** Run by exit(): libfclib ended the process inside a call. */
      extern "C" void
      report_libfclib_exit()
      {
        ActiveCall &call = active_call();
        if (!call.active)
          return;
        const int error_number = errno;
        call.active            = false;
        restore_stderr(call);
        std::string message = "FCLIB file `" + call.file + "': ";
        if (call.action == "write")
        {
          message +=
            "cannot write it: " + write_failure_cause(call.file, error_number);
          if (!call.partial_file.empty())
          {
            std::error_code error;
            std::filesystem::remove(call.partial_file, error);
            message += " (the partial file `" + call.partial_file +
                       "' is removed, an existing `" + call.file + "' is kept)";
          }
        }
        else
          message += "cannot " + call.action +
                     " it: an HDF5 call in libfclib failed (the file is "
                     "damaged)";
        std::fprintf(stderr,
                     "%s: %s.\n",
                     program_invocation_short_name,
                     message.c_str());
        std::fflush(stderr);
      }
    } // namespace


    std::string
    write_failure_cause(const std::string &path, const int error_number)
    {
      std::error_code       error;
      std::filesystem::path folder =
        std::filesystem::absolute(path, error).parent_path();
      struct statvfs info;
      // "full": less than 64 KiB left for an unprivileged writer
      if (error_number == ENOSPC ||
          (statvfs(folder.c_str(), &info) == 0 &&
           static_cast<unsigned long long>(info.f_bavail) * info.f_frsize <
             (64ull << 10)))
        return std::strerror(ENOSPC);
      for (const int believed : {EIO, EDQUOT, EFBIG, EROFS, EACCES})
        if (error_number == believed)
          return std::strerror(error_number);
      return "an HDF5 call failed";
    }


    LibfclibCall::LibfclibCall(const std::string &file,
                               const std::string &action,
                               const std::string &partial_file)
    {
      // the call record first: exit() destroys it only after the handler,
      // which is registered later, has run
      ActiveCall       &call       = active_call();
      static const bool registered = (std::atexit(report_libfclib_exit) == 0);
      (void)registered;
      Assert(!call.active, dealii::ExcInternalError());
      call.file         = file;
      call.action       = action;
      call.partial_file = partial_file;
      std::fflush(stderr);
      call.saved_stderr = dup(STDERR_FILENO);
      const int null    = open("/dev/null", O_WRONLY | O_CLOEXEC);
      if (call.saved_stderr >= 0 && null >= 0)
        dup2(null, STDERR_FILENO);
      if (null >= 0)
        close(null);
      call.active = true;
    }


    LibfclibCall::~LibfclibCall()
    {
      ActiveCall &call = active_call();
      call.active      = false;
      restore_stderr(call);
    }
  } // namespace fclib
} // namespace dualcontact
