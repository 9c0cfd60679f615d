#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    /**
     * The folder a run writes into, with all-or-nothing semantics: files are
     * written under temporary names (".name.tmp") and renamed to their final
     * names only by commit(), after every file has been written.  If the
     * object is destroyed without commit() (an error while writing), the
     * temporary files are removed, and so are the folders this object
     * created.
     *
     * The constructor only checks, and creates nothing: the folder must be
     * an existing writable directory, or creatable (every existing part of
     * the path is a directory, the deepest existing one is writable).  This
     * check runs while the parameters are read, before any computation.
     */
    class OutputFolder
    {
    public:
      /**
       * @p path is relative to the current working directory;
       * @p parameter_location names the parameter in error messages.
       */
      OutputFolder(const std::string &path,
                   const std::string &parameter_location);
      ~OutputFolder();

      OutputFolder(const OutputFolder &) = delete;
      OutputFolder &
      operator=(const OutputFolder &) = delete;

      /** The folder as given in the parameter file. */
      const std::string &
      path() const;

      /**
       * Write the file @p name (no folders) through @p writer into its
       * temporary name; creates the folder on first use.
       */
      void
      write(const std::string                         &name,
            const std::function<void(std::ostream &)> &writer);

      /** Rename all written files to their final names. */
      void
      commit();

      /** The final names of the files written so far. */
      const std::vector<std::string> &
      file_names() const;

    private:
      void
      create_folder();
      void
      remove_uncommitted();

      std::string              path_;
      std::vector<std::string> created_folders_;
      std::vector<std::string> file_names_;
      bool                     committed_ = false;
    };
  } // namespace io
} // namespace dualcontact
