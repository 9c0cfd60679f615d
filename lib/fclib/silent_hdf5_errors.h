#pragma once

#include <hdf5.h>

namespace dualcontact
{
  namespace fclib
  {
    /**
     * HDF5 prints its error stack (some 40 lines) for every failed call,
     * also inside libfclib: silenced while an object of this class lives;
     * the messages of this module name the file and what went wrong
     * instead.
     */
    class SilentHdf5Errors
    {
    public:
      SilentHdf5Errors()
      {
        H5Eget_auto2(H5E_DEFAULT, &old_function_, &old_data_);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
      }
      ~SilentHdf5Errors()
      {
        H5Eset_auto2(H5E_DEFAULT, old_function_, old_data_);
      }
      SilentHdf5Errors(const SilentHdf5Errors &) = delete;
      SilentHdf5Errors &
      operator=(const SilentHdf5Errors &) = delete;

    private:
      H5E_auto2_t old_function_ = nullptr;
      void       *old_data_     = nullptr;
    };
  } // namespace fclib
} // namespace dualcontact
