#include <deal.II/base/exceptions.h>

#include <io/output_folder.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <system_error>

namespace dualcontact
{
  namespace io
  {
    namespace fs = std::filesystem;

    namespace
    {
      std::string
      temporary_name(const std::string &name)
      {
        return "." + name + ".tmp";
      }

      const std::string lock_file_name     = ".dualcontact.lock";
      const std::string manifest_file_name = ".dualcontact_files";

      /** The text of errno @p number ("No space left on device"). */
      std::string
      cause(const int number)
      {
        return number == 0 ?
                 std::string("cause unknown") :
                 std::error_code(number, std::generic_category()).message();
      }

      /**
       * What the signal handler removes: files (temporaries, the lock file)
       * and folders this process created.  The storage is reserved up front
       * and only appended to, so that the handler reads it without
       * allocating; an entry counts once the counter includes it.
       */
      struct CleanupList
      {
        static constexpr std::size_t capacity = 1 << 14;

        CleanupList()
        {
          files.reserve(capacity);
          folders.reserve(capacity);
        }

        void
        add_file(const std::string &path)
        {
          if (files.size() < capacity)
          {
            files.push_back(path);
            n_files = files.size();
          }
        }

        void
        add_folder(const std::string &path)
        {
          if (folders.size() < capacity)
          {
            folders.push_back(path);
            n_folders = folders.size();
          }
        }

        /** After a commit: nothing of it is temporary any more. */
        void
        clear()
        {
          n_files   = 0;
          n_folders = 0;
          files.clear();
          folders.clear();
        }

        std::vector<std::string> files;
        std::vector<std::string> folders;
        std::atomic<std::size_t> n_files{0};
        std::atomic<std::size_t> n_folders{0};
      };

      /**
       * Whether @p part (of the output folder @p path) exists; throws naming
       * the folder, the parameter (@p parameter_location, if not empty) and
       * the cause if that cannot be told (std::filesystem would throw its
       * own filesystem_error, which names neither).  The constructor checks
       * with the parameter named; create_folder() checks again, as the
       * path may have changed since.
       */
      bool
      exists_or_throw(const fs::path    &part,
                      const std::string &path,
                      const std::string &parameter_location)
      {
        std::error_code error;
        const bool      found = fs::exists(part, error);
        AssertThrow(!error,
                    dealii::ExcMessage(
                      "Cannot write the output folder `" + path + "'" +
                      (parameter_location.empty() ? std::string() :
                                                    " " + parameter_location) +
                      ": `" + part.string() + "': " + error.message() + "."));
        return found;
      }

      CleanupList &
      cleanup_list()
      {
        static CleanupList list;
        return list;
      }

      /**
       * Run by exit(): what an uncommitted run left (nothing after a
       * commit, which empties the list; after a failure the destructor has
       * removed them already, and this finds nothing).
       */
      extern "C" void
      remove_temporaries_at_exit()
      {
        CleanupList &list = cleanup_list();
        for (std::size_t i = 0; i < list.n_files; ++i)
          (void)unlink(list.files[i].c_str());
        for (std::size_t i = list.n_folders; i > 0; --i)
          (void)rmdir(list.folders[i - 1].c_str());
      }

      extern "C" void
      remove_temporaries_and_exit(const int signal_number)
      {
        // only async-signal-safe calls here: unlink, rmdir, write, _exit
        CleanupList &list = cleanup_list();
        for (std::size_t i = 0; i < list.n_files; ++i)
          (void)unlink(list.files[i].c_str());
        for (std::size_t i = list.n_folders; i > 0; --i)
          (void)rmdir(list.folders[i - 1].c_str());
        const char message[] =
          "\ndualcontact: interrupted; temporary files removed.\n";
        [[maybe_unused]] const ssize_t written =
          write(STDERR_FILENO, message, sizeof(message) - 1);
        _exit(128 + signal_number);
      }
    } // namespace


    void
    OutputFolder::install_signal_handlers()
    {
      (void)cleanup_list(); // reserve its storage now, not in the handler
      // a library that ends the process with exit() (libfclib does when an
      // HDF5 call fails) skips the destructors that remove the temporaries
      std::atexit(remove_temporaries_at_exit);
      struct sigaction action;
      std::memset(&action, 0, sizeof(action));
      action.sa_handler = remove_temporaries_and_exit;
      sigemptyset(&action.sa_mask);
      for (const int signal_number : {SIGINT, SIGTERM, SIGHUP})
        sigaction(signal_number, &action, nullptr);
    }


    void
    OutputFolder::lock()
    {
      create_folder();
      const std::string lock_path = (fs::path(path_) / lock_file_name).string();
      while (lock_fd_ < 0)
      {
        const int fd =
          open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        AssertThrow(fd >= 0,
                    dealii::ExcMessage(
                      "Cannot create the lock file `" + lock_path +
                      "' of the output folder: " + cause(errno) + "."));
        if (flock(fd, LOCK_EX | LOCK_NB) != 0)
        {
          const int  error    = errno;
          char       text[32] = {};
          const auto n        = pread(fd, text, sizeof(text) - 1, 0);
          close(fd);
          const std::string holder =
            n > 0 ? std::string(text, text + n) : std::string("unknown\n");
          AssertThrow(error != EWOULDBLOCK,
                      dealii::ExcMessage(
                        "The output folder `" + path_ +
                        "' is in use by another dualcontact run (process " +
                        holder.substr(0, holder.find('\n')) +
                        ", which holds `" + lock_path +
                        "'): two runs into one folder would mix their "
                        "files. Wait for it to finish, or choose another "
                        "`Output folder'."));
          AssertThrow(false,
                      dealii::ExcMessage("Cannot lock `" + lock_path +
                                         "': " + cause(error) + "."));
        }
        // the previous holder removes the file when it is done: if it did
        // so after we opened it, our lock is on a file nobody else sees
        struct stat ours, named;
        if (fstat(fd, &ours) == 0 && stat(lock_path.c_str(), &named) == 0 &&
            ours.st_ino == named.st_ino && ours.st_dev == named.st_dev)
          lock_fd_ = fd;
        else
          close(fd);
      }
      const std::string pid = std::to_string(getpid()) + "\n";
      if (ftruncate(lock_fd_, 0) != 0 ||
          pwrite(lock_fd_, pid.data(), pid.size(), 0) !=
            static_cast<ssize_t>(pid.size()))
      {
        // the lock holds all the same; only the message of a second run
        // cannot name this process
      }
      cleanup_list().add_file(lock_path);
    }


    void
    OutputFolder::unlock()
    {
      if (lock_fd_ < 0)
        return;
      // remove the file while still holding the lock (see lock())
      (void)unlink((fs::path(path_) / lock_file_name).c_str());
      close(lock_fd_);
      lock_fd_ = -1;
    }


    void
    OutputFolder::remove_stale_files() const
    {
      const fs::path        manifest = fs::path(path_) / manifest_file_name;
      std::ifstream         in(manifest);
      std::set<std::string> written(file_names_.begin(), file_names_.end());
      written.insert(other_processes_files_.begin(),
                     other_processes_files_.end());
      std::string name;
      while (std::getline(in, name))
        if (!name.empty() && name.find('/') == std::string::npos &&
            name[0] != '.' && written.count(name) == 0)
        {
          std::error_code error;
          if (fs::is_regular_file(fs::path(path_) / name, error))
            fs::remove(fs::path(path_) / name, error);
        }
      in.close();
      const fs::path temporary =
        fs::path(path_) / temporary_name(manifest_file_name);
      {
        std::ofstream out(temporary);
        for (const auto &file : file_names_)
          out << file << "\n";
        for (const auto &file : other_processes_files_)
          out << file << "\n";
        out.close();
        AssertThrow(out,
                    dealii::ExcMessage("Cannot write the file `" +
                                       temporary.string() +
                                       "': " + cause(errno) + "."));
      }
      std::error_code error;
      fs::rename(temporary, manifest, error);
      AssertThrow(!error,
                  dealii::ExcMessage("Cannot rename `" + temporary.string() +
                                     "' to `" + manifest.string() +
                                     "': " + error.message() + "."));
    }


    OutputFolder::OutputFolder(const std::string &path,
                               const std::string &parameter_location)
        : path_(path)
    {
      AssertThrow(!path.empty(),
                  dealii::ExcMessage("The output folder name is empty " +
                                     parameter_location + "."));
      // Walk up to the deepest part of the path that exists: it must be a
      // writable directory.
      fs::path existing = fs::absolute(fs::path(path)).lexically_normal();
      std::error_code error;
      // a part of the path that cannot be looked at (a symbolic-link loop,
      // a folder without search permission) is an error, not a part that
      // does not exist
      while (!exists_or_throw(existing, path, parameter_location) &&
             existing.has_parent_path() && existing != existing.parent_path())
        existing = existing.parent_path();
      AssertThrow(fs::is_directory(existing, error),
                  dealii::ExcMessage("Cannot write the output folder `" + path +
                                     "' " + parameter_location + ": `" +
                                     existing.string() +
                                     "' exists and is not a directory."));
      AssertThrow(access(existing.c_str(), W_OK | X_OK) == 0,
                  dealii::ExcMessage("Cannot write the output folder `" + path +
                                     "' " + parameter_location +
                                     ": the directory `" + existing.string() +
                                     "' is not writable."));
    }


    OutputFolder::~OutputFolder()
    {
      if (!committed_)
        remove_uncommitted();
      unlock();
    }


    const std::string &
    OutputFolder::path() const
    {
      return path_;
    }


    const std::vector<std::string> &
    OutputFolder::file_names() const
    {
      return file_names_;
    }


    void
    OutputFolder::list_file_of_other_process(const std::string &name)
    {
      AssertThrow(!committed_, dealii::ExcInternalError());
      Assert(name.find('/') == std::string::npos, dealii::ExcInternalError());
      other_processes_files_.push_back(name);
    }


    void
    OutputFolder::create_folder()
    {
      // remember which folders are new, so that a failed run removes them
      std::vector<fs::path> missing;
      for (fs::path folder = fs::absolute(fs::path(path_)).lexically_normal();
           !exists_or_throw(folder, path_, "");
           folder = folder.parent_path())
        missing.push_back(folder);
      for (auto folder = missing.rbegin(); folder != missing.rend(); ++folder)
      {
        // under MPI several processes may create it at once: a folder that
        // exists when create_directory() is called is not an error (and not
        // ours to remove)
        std::error_code error;
        const bool      created = fs::create_directory(*folder, error);
        AssertThrow(!error,
                    dealii::ExcMessage("Cannot create the output folder `" +
                                       folder->string() +
                                       "': " + error.message()));
        if (created)
        {
          created_folders_.push_back(folder->string());
          cleanup_list().add_folder(folder->string());
        }
      }
    }


    void
    OutputFolder::write(const std::string                         &name,
                        const std::function<void(std::ostream &)> &writer)
    {
      AssertThrow(!committed_, dealii::ExcInternalError());
      if (file_names_.empty())
        create_folder();
      const fs::path temporary = fs::path(path_) / temporary_name(name);
      file_names_.push_back(name);
      cleanup_list().add_file(temporary.string());
      errno = 0;
      std::ofstream out(temporary);
      AssertThrow(out,
                  dealii::ExcMessage("Cannot write the file `" +
                                     temporary.string() + "': " + cause(errno) +
                                     "."));
      try
      {
        writer(out);
      }
      catch (const dealii::ExceptionBase &)
      {
        // deal.II's writers end with ExcIO ("An input/output error has
        // occurred.") when the stream failed: name the file and the cause
        const int number = errno;
        if (out)
          throw; // the writer's own error, which says what it is
        AssertThrow(false, dealii::ExcMessage(write_failure(name, number)));
      }
      out.close();
      AssertThrow(out, dealii::ExcMessage(write_failure(name, errno)));
    }


    std::string
    OutputFolder::write_failure(const std::string &name,
                                const int          error_number) const
    {
      // the file the user asked for, not the temporary it is written to
      // first (which the cleanup removes, with everything of this run)
      return "Writing the file `" + (fs::path(path_) / name).string() +
             "' failed: " + cause(error_number) + ".";
    }


    void
    OutputFolder::commit()
    {
      for (const auto &name : file_names_)
      {
        std::error_code error;
        fs::rename(fs::path(path_) / temporary_name(name),
                   fs::path(path_) / name,
                   error);
        AssertThrow(!error,
                    dealii::ExcMessage("Cannot rename the output file `" +
                                       name + "' in `" + path_ +
                                       "': " + error.message()));
      }
      if (lock_fd_ >= 0)
        remove_stale_files();
      committed_ = true;
      cleanup_list().clear();
    }


    void
    OutputFolder::remove_uncommitted()
    {
      std::error_code error;
      for (const auto &name : file_names_)
        fs::remove(fs::path(path_) / temporary_name(name), error);
      unlock();
      for (auto folder = created_folders_.rbegin();
           folder != created_folders_.rend();
           ++folder)
        fs::remove(*folder, error); // only removes empty folders
    }
  } // namespace io
} // namespace dualcontact
