#include <deal.II/base/exceptions.h>

#include <fclib/file_layout.h>
#include <fclib/silent_hdf5_errors.h>
#include <util/available_memory.h>

#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <vector>

namespace dualcontact
{
  namespace fclib
  {
    namespace
    {
      /** An HDF5 handle closed by @p close when the object goes away. */
      class Handle
      {
      public:
        Handle(const hid_t id, herr_t (*close)(hid_t))
            : id_(id)
            , close_(close)
        {
        }
        ~Handle()
        {
          if (id_ >= 0)
            close_(id_);
        }
        Handle(const Handle &) = delete;
        Handle &
        operator=(const Handle &) = delete;
        hid_t
        get() const
        {
          return id_;
        }
        bool
        valid() const
        {
          return id_ >= 0;
        }

      private:
        hid_t id_;
        herr_t (*close_)(hid_t);
      };


      /** The data sets of one file, read through HDF5 without libfclib. */
      class LayoutReader
      {
      public:
        explicit LayoutReader(const std::string &path)
            : path_(path)
            , file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                    H5Fclose)
        {
          AssertThrow(file_.valid(),
                      dealii::ExcMessage("`" + path +
                                         "' is a truncated or corrupt HDF5 "
                                         "file (HDF5 cannot open it)"));
          std::error_code error;
          file_size_ = std::filesystem::file_size(path, error);
          AssertThrow(!error,
                      dealii::ExcMessage("Cannot read the size of `" + path +
                                         "': " + error.message()));
        }

        bool
        exists(const std::string &name) const
        {
          // every part of the path must exist for H5Lexists on the next
          std::string::size_type at = 0;
          while ((at = name.find('/', at + 1)) != std::string::npos)
            if (H5Lexists(file_.get(),
                          name.substr(0, at).c_str(),
                          H5P_DEFAULT) <= 0)
              return false;
          return H5Lexists(file_.get(), name.c_str(), H5P_DEFAULT) > 0;
        }

        /**
         * The number of entries of the data set @p name (which must
         * exist), after checking that its bytes lie inside the file.
         */
        std::int64_t
        extent(const std::string &name) const
        {
          AssertThrow(exists(name), error(name, "is missing"));
          const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT),
                           H5Dclose);
          AssertThrow(set.valid(), error(name, "cannot be opened"));
          const Handle space(H5Dget_space(set.get()), H5Sclose);
          AssertThrow(space.valid(), error(name, "has no data space"));
          const hssize_t n = H5Sget_simple_extent_npoints(space.get());
          AssertThrow(n >= 0, error(name, "has no extent"));
          // contiguous data: its bytes must be inside the file (chunked
          // and compact data sets have no single offset; HDF5 checks those
          // when it reads them)
          const haddr_t offset = H5Dget_offset(set.get());
          if (offset != HADDR_UNDEF)
          {
            const std::uint64_t stored = H5Dget_storage_size(set.get());
            AssertThrow(offset <= file_size_ && stored <= file_size_ - offset,
                        error(name,
                              "lies beyond the end of the file (" +
                                std::to_string(stored) + " bytes at offset " +
                                std::to_string(offset) + " of a file of " +
                                std::to_string(file_size_) +
                                " bytes): the file was cut short"));
          }
          return n;
        }

        /** The one integer in the data set @p name. */
        std::int64_t
        scalar(const std::string &name) const
        {
          AssertThrow(extent(name) == 1,
                      error(name,
                            "must hold one value, it holds " +
                              std::to_string(extent(name))));
          const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT),
                           H5Dclose);
          long long    value = 0;
          AssertThrow(H5Dread(set.get(),
                              H5T_NATIVE_LLONG,
                              H5S_ALL,
                              H5S_ALL,
                              H5P_DEFAULT,
                              &value) >= 0,
                      error(name, "cannot be read as an integer"));
          return value;
        }

        /**
         * Reads the whole data set @p name, converted to @p memory_type as
         * libfclib will read it: a damaged file (a flipped byte in a chunk,
         * a heap or a type message) makes HDF5 fail there, and libfclib
         * end the process without naming the file.
         */
        void
        require_readable(const std::string &name, const hid_t memory_type) const
        {
          const std::int64_t n = extent(name);
          const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT),
                           H5Dclose);
          AssertThrow(set.valid(), error(name, "cannot be opened"));
          read_into_buffer(name, set.get(), memory_type, n);
        }

        /** The string data set @p name (libfclib's info records). */
        void
        require_readable_string(const std::string &name) const
        {
          const std::int64_t n = extent(name);
          const Handle set(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT),
                           H5Dclose);
          AssertThrow(set.valid(), error(name, "cannot be opened"));
          const Handle type(H5Dget_type(set.get()), H5Tclose);
          AssertThrow(type.valid() && H5Tget_class(type.get()) == H5T_STRING,
                      error(name, "is not a string"));
          // libfclib reads fixed-length strings only (H5LT)
          AssertThrow(H5Tis_variable_str(type.get()) == 0,
                      error(name, "is a variable-length string"));
          read_into_buffer(name, set.get(), type.get(), n);
        }

        /** The group @p name must open (libfclib opens it). */
        void
        require_group(const std::string &name) const
        {
          AssertThrow(exists(name), error(name, "is missing"));
          const Handle group(H5Gopen2(file_.get(), name.c_str(), H5P_DEFAULT),
                             H5Gclose);
          AssertThrow(group.valid(),
                      error(name,
                            "cannot be opened as a group (the file is "
                            "damaged)"));
          // libfclib looks names up by iterating the group (H5LTfind_
          // dataset): a damaged link table fails there
          const auto each_link =
            [](hid_t, const char *, const H5L_info_t *, void *) -> herr_t
          { return 0; };
          AssertThrow(H5Literate(group.get(),
                                 H5_INDEX_NAME,
                                 H5_ITER_NATIVE,
                                 nullptr,
                                 each_link,
                                 nullptr) >= 0,
                      error(name,
                            "cannot be listed: its table of names is damaged"));
        }

        /** Requires the data set @p name to have @p expected entries. */
        void
        require_extent(const std::string &name,
                       const std::int64_t expected,
                       const std::string &why) const
        {
          const std::int64_t n = extent(name);
          AssertThrow(n == expected,
                      error(name,
                            "holds " + std::to_string(n) + " entries, " + why +
                              " says " + std::to_string(expected)));
        }

        dealii::ExcMessage
        error(const std::string &name, const std::string &what) const
        {
          return dealii::ExcMessage("FCLIB file `" + path_ + "': " + name +
                                    " " + what);
        }

      private:
        void
        read_into_buffer(const std::string &name,
                         const hid_t        set,
                         const hid_t        memory_type,
                         const std::int64_t n) const
        {
          const std::uint64_t bytes =
            std::uint64_t(std::max<std::int64_t>(n, 1)) *
            H5Tget_size(memory_type);
          const std::uint64_t available = util::available_memory();
          AssertThrow(
            available == 0 || bytes <= available,
            error(name,
                  "needs " + std::to_string(bytes) + " bytes, more than the " +
                    std::to_string(available) + " bytes of memory available"));
          std::vector<char> buffer(bytes);
          AssertThrow(H5Dread(set,
                              memory_type,
                              H5S_ALL,
                              H5S_ALL,
                              H5P_DEFAULT,
                              buffer.data()) >= 0,
                      error(name,
                            "cannot be read: HDF5 fails on its data (the "
                            "file is damaged)"));
        }

        std::string      path_;
        SilentHdf5Errors silent_; // before file_: H5Fopen may fail
        Handle           file_;
        std::uint64_t    file_size_ = 0;
      };


      struct MatrixSize
      {
        std::int64_t m, n;
      };


      /** The header of the matrix group @p group checked against p, i, x. */
      MatrixSize
      check_matrix(const LayoutReader &file, const std::string &group)
      {
        const std::int64_t m     = file.scalar(group + "/m");
        const std::int64_t n     = file.scalar(group + "/n");
        const std::int64_t nz    = file.scalar(group + "/nz");
        const std::int64_t nzmax = file.scalar(group + "/nzmax");
        // libfclib keeps the sizes in int
        constexpr std::int64_t int_max = std::numeric_limits<int>::max();
        AssertThrow(m >= 0 && n >= 0 && m < int_max && n < int_max,
                    file.error(group,
                               "has " + std::to_string(m) + " x " +
                                 std::to_string(n) + " entries (m, n)"));
        AssertThrow(nzmax >= 0 && nzmax <= int_max,
                    file.error(group + "/nzmax",
                               "is " + std::to_string(nzmax)));
        if (nz >= 0) // triplets
        {
          AssertThrow(nz <= nzmax,
                      file.error(group + "/nz",
                                 "is " + std::to_string(nz) +
                                   ", more than nzmax = " +
                                   std::to_string(nzmax)));
          for (const char *array : {"/p", "/i", "/x"})
            file.require_extent(group + array, nz, group + "/nz (triplets)");
        }
        else
        {
          AssertThrow(nz == -1 || nz == -2,
                      file.error(group + "/nz",
                                 "is " + std::to_string(nz) +
                                   ": neither triplets (>= 0) nor compressed "
                                   "columns (-1) or rows (-2)"));
          const std::int64_t n_pointers = (nz == -1 ? n : m) + 1;
          file.require_extent(group + "/p",
                              n_pointers,
                              std::string(nz == -1 ? "n" : "m") +
                                " + 1 (compressed " +
                                (nz == -1 ? "columns" : "rows") + ")");
          for (const char *array : {"/i", "/x"})
            file.require_extent(group + array, nzmax, group + "/nzmax");
        }
        return {m, n};
      }


      /**
       * Every data set of the matrix group @p group that libfclib reads,
       * read here first (check_matrix() has checked their sizes).
       */
      void
      check_matrix_readable(const LayoutReader &file, const std::string &group)
      {
        file.require_group(group);
        for (const char *name : {"/nzmax", "/m", "/n", "/nz", "/p", "/i"})
          file.require_readable(group + name, H5T_NATIVE_INT);
        file.require_readable(group + "/x", H5T_NATIVE_DOUBLE);
        // the optional matrix info: libfclib reads it when `conditioning'
        // is there
        if (file.exists(group + "/conditioning"))
        {
          for (const char *name : {"/conditioning", "/determinant"})
            file.require_readable(group + name, H5T_NATIVE_DOUBLE);
          file.require_readable(group + "/rank", H5T_NATIVE_INT);
          if (file.exists(group + "/comment"))
            file.require_readable_string(group + "/comment");
        }
      }


      /**
       * What libfclib reads besides the matrices: the groups, spacedim, the
       * vectors, the info strings and the solution.  Read here first, so
       * that a damaged file is refused naming the data set: libfclib would
       * end the process on the first HDF5 call that fails.
       */
      void
      check_readable(const LayoutReader &file,
                     const std::string  &root,
                     const Form          form,
                     const bool          has_solution)
      {
        file.require_group(root);
        file.require_readable(root + "/spacedim", H5T_NATIVE_INT);
        file.require_group(root + "/vectors");
        for (const char *name : form == Form::local ?
                                  std::vector<const char *>{"/q", "/mu"} :
                                  std::vector<const char *>{"/f", "/w", "/mu"})
          file.require_readable(root + "/vectors" + name, H5T_NATIVE_DOUBLE);
        if (file.exists(root + "/info"))
        {
          file.require_group(root + "/info");
          for (const char *name : {"/title", "/description", "/math_info"})
            if (file.exists(root + "/info" + name))
              file.require_readable_string(root + "/info" + name);
        }
        if (!has_solution)
          return;
        // libfclib reads u and r (and v of a global problem) together
        file.require_group("/solution");
        for (const char *name : {"/solution/r", "/solution/u"})
          file.require_readable(name, H5T_NATIVE_DOUBLE);
        if (form == Form::global)
          file.require_readable("/solution/v", H5T_NATIVE_DOUBLE);
      }
    } // namespace


    FileLayout::FileLayout(const std::string &path, const Form form)
    {
      const LayoutReader file(path);
      const std::string  root =
        form == Form::local ? "/fclib_local" : "/fclib_global";
      const std::int64_t spacedim      = file.scalar(root + "/spacedim");
      std::int64_t       velocity_size = 0; // M's order (global)
      AssertThrow(spacedim == 2 || spacedim == 3,
                  file.error(root + "/spacedim",
                             "is " + std::to_string(spacedim) +
                               ", not 2 or 3"));
      if (form == Form::local)
      {
        for (const char *name : {"/V", "/R", "/vectors/s"})
          AssertThrow(!file.exists(root + name),
                      file.error(root + name,
                                 "is present: local problems with equality "
                                 "constraints (V, R, s) are not supported"));
        const MatrixSize W = check_matrix(file, root + "/W");
        AssertThrow(W.m == W.n,
                    file.error(root + "/W",
                               "is " + std::to_string(W.m) + " x " +
                                 std::to_string(W.n) + ", not square"));
        contact_size_ = W.m;
      }
      else
      {
        for (const char *name : {"/G", "/vectors/b"})
          AssertThrow(!file.exists(root + name),
                      file.error(root + name,
                                 "is present: global problems with equality "
                                 "constraints (G, b) are not supported"));
        const MatrixSize M = check_matrix(file, root + "/M");
        const MatrixSize H = check_matrix(file, root + "/H");
        AssertThrow(M.m == M.n,
                    file.error(root + "/M",
                               "is " + std::to_string(M.m) + " x " +
                                 std::to_string(M.n) + ", not square"));
        AssertThrow(H.m == M.m,
                    file.error(root + "/H",
                               "has " + std::to_string(H.m) + " rows, M has " +
                                 std::to_string(M.m)));
        file.require_extent(root + "/vectors/f", M.m, "the order of M");
        velocity_size = M.m;
        file.require_extent(root + "/vectors/w", H.n, "the columns of H");
        contact_size_ = H.n;
      }
      AssertThrow(contact_size_ % spacedim == 0,
                  file.error(root,
                             "has " + std::to_string(contact_size_) +
                               " contact unknowns, not a multiple of the "
                               "dimension " +
                               std::to_string(spacedim)));
      if (form == Form::local)
        file.require_extent(root + "/vectors/q",
                            contact_size_,
                            "the order of W");
      file.require_extent(root + "/vectors/mu",
                          contact_size_ / spacedim,
                          "the number of contacts");
      // libfclib sizes the solution's arrays from the problem's matrices
      // and reads whatever /solution holds into them
      has_solution_ = file.exists("/solution/r");
      for (const char *name : {"/solution/r", "/solution/u"})
        if (file.exists(name))
          file.require_extent(name,
                              contact_size_,
                              "the number of contact unknowns");
      if (file.exists("/solution/v"))
        file.require_extent("/solution/v",
                            velocity_size,
                            form == Form::global ?
                              "the order of M" :
                              "a local problem (no velocities)");
      AssertThrow(!file.exists("/solution/l"),
                  file.error("/solution/l",
                             "is present: multipliers of equality "
                             "constraints are not supported"));
      if (form == Form::local)
        check_matrix_readable(file, root + "/W");
      else
      {
        check_matrix_readable(file, root + "/M");
        check_matrix_readable(file, root + "/H");
      }
      check_readable(file, root, form, has_solution_);
    }


    std::uint64_t
    FileLayout::contact_size() const
    {
      return contact_size_;
    }


    bool
    FileLayout::has_solution() const
    {
      return has_solution_;
    }


    void
    check_compressed_pointers(const int         *p,
                              const std::int64_t n_pointers,
                              const std::int64_t nzmax,
                              const std::string &what)
    {
      AssertThrow(n_pointers >= 1 && p[0] == 0,
                  dealii::ExcMessage(what + ": the first pointer is " +
                                     std::to_string(p[0]) + ", not 0"));
      for (std::int64_t k = 1; k < n_pointers; ++k)
        AssertThrow(p[k] >= p[k - 1] && p[k] <= nzmax,
                    dealii::ExcMessage(
                      what + ": pointer " + std::to_string(k) + " is " +
                      std::to_string(p[k]) + " after " +
                      std::to_string(p[k - 1]) +
                      " (pointers must not decrease and not exceed nzmax = " +
                      std::to_string(nzmax) + ")"));
    }
  } // namespace fclib
} // namespace dualcontact
