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
     * The files of a commit are listed in `.dualcontact_files'; the next
     * commit into the same folder removes the files of that list that it
     * does not write itself (a previous scene's contact_2.vtu), after its
     * own files are renamed in, so that the folder holds one run's files.
     * Errors name the file and the cause (no space left, permission).
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

      /**
       * Under MPI: record in this process' list of the run's files
       * (`.dualcontact_files', kept by the process that holds the lock) the
       * file @p name that another process writes (its piece of a body), so
       * that commit() keeps it, and the next run on fewer processes removes
       * it as stale.
       */
      void
      list_file_of_other_process(const std::string &name);

      /**
       * Take the folder for this run, before any computation: create it (a
       * failed run removes it again), and hold an exclusive lock (flock) on
       * its file `.dualcontact.lock', which records the process id.  A
       * second run into the same folder is refused at once with a message
       * naming the folder and the process that holds it: waiting would
       * only delay a mistake (two scenes writing one folder overwrite each
       * other's results) while holding the memory of a meshed scene.  The
       * lock file is removed when this object goes away.  Under MPI, only
       * one process calls this.
       */
      void
      lock();

      /**
       * Remove the temporary files, the lock file and the folders this
       * process created, and end the process with 128 + the signal's
       * number on SIGINT and SIGTERM (and SIGHUP): an interrupted run
       * leaves no hidden `.name.tmp' files and no partial output.  Called
       * once by the application.
       */
      static void
      install_signal_handlers();

    private:
      void
      create_folder();
      void
      remove_uncommitted();
      void
      remove_stale_files() const;
      void
      unlock();
      /** "Writing the file `FOLDER/NAME' failed: CAUSE." */
      std::string
      write_failure(const std::string &name, const int error_number) const;

      std::string              path_;
      std::vector<std::string> created_folders_;
      std::vector<std::string> file_names_;
      std::vector<std::string> other_processes_files_;
      bool                     committed_ = false;
      int                      lock_fd_   = -1;
    };
  } // namespace io
} // namespace dualcontact
