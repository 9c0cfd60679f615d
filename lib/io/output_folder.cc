#include <deal.II/base/exceptions.h>

#include <io/output_folder.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

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
    } // namespace


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
      while (!fs::exists(existing, error) && existing.has_parent_path() &&
             existing != existing.parent_path())
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
    OutputFolder::create_folder()
    {
      // remember which folders are new, so that a failed run removes them
      std::vector<fs::path> missing;
      for (fs::path folder = fs::absolute(fs::path(path_)).lexically_normal();
           !fs::exists(folder);
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
          created_folders_.push_back(folder->string());
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
      std::ofstream out(temporary);
      AssertThrow(out,
                  dealii::ExcMessage("Cannot write the file `" +
                                     temporary.string() + "'."));
      writer(out);
      out.close();
      AssertThrow(out,
                  dealii::ExcMessage("Writing the file `" + temporary.string() +
                                     "' failed."));
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
      committed_ = true;
    }


    void
    OutputFolder::remove_uncommitted()
    {
      std::error_code error;
      for (const auto &name : file_names_)
        fs::remove(fs::path(path_) / temporary_name(name), error);
      for (auto folder = created_folders_.rbegin();
           folder != created_folders_.rend();
           ++folder)
        fs::remove(*folder, error); // only removes empty folders
    }
  } // namespace io
} // namespace dualcontact
