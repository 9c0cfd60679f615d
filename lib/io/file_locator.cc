#include <deal.II/base/exceptions.h>

#include <io/file_locator.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace dualcontact
{
  namespace io
  {
    namespace
    {
      bool
      is_readable_file(const std::filesystem::path &path)
      {
        std::error_code error;
        if (!std::filesystem::is_regular_file(path, error))
          return false;
        std::ifstream in(path);
        return static_cast<bool>(in);
      }
    } // namespace


    std::string
    locate_file(const std::string &name,
                const std::string &parameter_file_folder,
                const std::string &parameter_location)
    {
      AssertThrow(!name.empty(),
                  dealii::ExcMessage("No file name given " +
                                     parameter_location + "."));
      const std::filesystem::path        path(name);
      std::vector<std::filesystem::path> candidates{path};
      if (path.is_relative())
      {
        candidates.push_back(std::filesystem::path(parameter_file_folder) /
                             path);
        candidates.push_back(std::filesystem::path(DUALCONTACT_SOURCE_DIR) /
                             path);
      }
      std::string tried;
      for (const auto &candidate : candidates)
      {
        if (is_readable_file(candidate))
          return candidate.lexically_normal().string();
        tried += "\n    " + candidate.lexically_normal().string();
      }
      AssertThrow(false,
                  dealii::ExcMessage("Cannot open the file `" + name + "' " +
                                     parameter_location +
                                     ". Paths tried:" + tried));
      return {};
    }


    std::string
    folder_of(const std::string &file_name)
    {
      const std::filesystem::path parent =
        std::filesystem::path(file_name).parent_path();
      return parent.empty() ? std::string(".") : parent.string();
    }
  } // namespace io
} // namespace dualcontact
