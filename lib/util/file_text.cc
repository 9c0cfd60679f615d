#include <deal.II/base/exceptions.h>

#include <util/available_memory.h>
#include <util/file_text.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace dualcontact
{
  namespace util
  {
    std::string
    read_file_text(const std::string &filename, const std::string &what)
    {
      const std::string kind =
        (what.empty() ? std::string("file") : what + " file");
      // fopen() opens a directory, whose "size" from fseek/ftell is
      // anything up to LONG_MAX: refuse what is not a regular file
      std::error_code                    error;
      const std::filesystem::file_status status =
        std::filesystem::status(filename, error);
      AssertThrow(!std::filesystem::is_directory(status),
                  dealii::ExcMessage("Cannot read " + kind + " '" + filename +
                                     "': it is a directory."));
      AssertThrow(error || std::filesystem::is_regular_file(status),
                  dealii::ExcMessage("Cannot read " + kind + " '" + filename +
                                     "': it is not a regular file."));
      std::FILE *file = std::fopen(filename.c_str(), "rb");
      AssertThrow(file != nullptr,
                  dealii::ExcMessage("Cannot open " + kind + " '" + filename +
                                     "': " + std::strerror(errno) + "."));
      std::string content;
      std::fseek(file, 0, SEEK_END);
      const long size = std::ftell(file);
      std::fseek(file, 0, SEEK_SET);
      const std::uint64_t available = util::available_memory();
      if (size > 0 && available > 0 &&
          static_cast<std::uint64_t>(size) > available)
      {
        std::fclose(file);
        AssertThrow(false,
                    dealii::ExcMessage(
                      "Cannot read " + kind + " '" + filename + "': it has " +
                      std::to_string(size) + " bytes, more than the " +
                      std::to_string(available) +
                      " bytes of memory available (MemAvailable in "
                      "/proc/meminfo)."));
      }
      if (size > 0)
      {
        content.resize(static_cast<std::size_t>(size));
        const std::size_t n_read =
          std::fread(content.data(), 1, content.size(), file);
        const bool failed = std::ferror(file) != 0;
        const int  number = errno;
        content.resize(n_read);
        if (failed)
        {
          std::fclose(file);
          AssertThrow(false,
                      dealii::ExcMessage("Cannot read " + kind + " '" +
                                         filename +
                                         "': " + std::strerror(number) + "."));
        }
      }
      std::fclose(file);
      return content;
    }
  } // namespace util
} // namespace dualcontact
