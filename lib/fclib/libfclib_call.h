#pragma once

#include <fclib/silent_hdf5_errors.h>

#include <string>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * What a failed write of @p path is most likely due to, for messages:
     * "No space left on device" when its file system is (nearly) full or
     * @p error_number says so, the text of @p error_number when it is an
     * I/O error (EIO, EDQUOT, EFBIG, EROFS, EACCES), else "an HDF5 call
     * failed".  libfclib and HDF5 report no cause, and errno after them
     * may be left from an unrelated call (libfclib probes a new file with
     * fopen(), which sets ENOENT), so only these are believed.
     */
    std::string
    write_failure_cause(const std::string &path, const int error_number);

    /**
     * Around a call into libfclib, which ends the process with exit(1) when
     * an HDF5 call fails, after printing "./src/fclib.h: 621 => ERROR: HDF5
     * call failed" and naming no file, and leaves the file it was writing.
     * While an object of this class lives, HDF5's error stack and the
     * standard error stream (libfclib's message) are silenced; should
     * libfclib end the process, a handler run by exit() restores standard
     * error, removes @p partial_file (the temporary being written, if any)
     * and prints one line naming @p file, what was done (@p action: "read"
     * or "write") and the cause.  The exit code stays libfclib's 1.
     *
     * FileLayout reads every data set libfclib reads before it does, so
     * that a damaged file is refused with an exception naming the data set;
     * this is the net for what that check does not foresee, and for writes
     * (a full disk).  Objects of this class do not nest.
     */
    class LibfclibCall
    {
    public:
      LibfclibCall(const std::string &file,
                   const std::string &action,
                   const std::string &partial_file = "");
      ~LibfclibCall();

      LibfclibCall(const LibfclibCall &) = delete;
      LibfclibCall &
      operator=(const LibfclibCall &) = delete;

    private:
      SilentHdf5Errors silent_;
    };
  } // namespace fclib
} // namespace dualcontact
